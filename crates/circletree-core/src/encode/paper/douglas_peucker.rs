//! Douglas-Peucker on a closed ring (paper section 3.5: its points become zero-radius circles).
//! Iterative with an explicit stack, so a million vertices cannot overflow the call stack.
//! Cost: O(n log n) typical, O(n²) worst case.

use crate::geom::{dist, dist_to_segment, Pt};

/// Indices of the ring vertices Douglas-Peucker keeps at `tol`, ascending. The ring is open; it
/// is split at vertex 0 and at the vertex farthest from it, and each half simplified.
pub fn keep(ring: &[Pt], tol: f64) -> Vec<usize> {
    let n = ring.len();
    if n <= 3 {
        return (0..n).collect();
    }
    let far = (1..n)
        .max_by(|&a, &b| dist(ring[0], ring[a]).total_cmp(&dist(ring[0], ring[b])))
        .unwrap_or(n / 2);
    let mut kept = vec![false; n];
    kept[0] = true;
    kept[far] = true;
    // Segments as (start, end) indices along the ring; `end` may equal n, meaning vertex 0.
    let mut stack = vec![(0usize, far), (far, n)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (pa, pb) = (ring[a], ring[b % n]);
        let mut best = (0.0, 0usize);
        for (i, p) in ring.iter().enumerate().take(b).skip(a + 1) {
            let d = dist_to_segment(*p, pa, pb);
            if d > best.0 {
                best = (d, i);
            }
        }
        if best.0 > tol {
            kept[best.1] = true;
            stack.push((a, best.1));
            stack.push((best.1, b));
        }
    }
    (0..n).filter(|&i| kept[i]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_with_noise_keeps_corners() {
        let ring = [
            [0.0, 0.0],
            [5.0, 0.1],
            [10.0, 0.0],
            [10.0, 5.0],
            [10.0, 10.0],
            [5.0, 10.0],
            [0.0, 10.0],
            [0.1, 5.0],
        ];
        assert_eq!(keep(&ring, 0.5), vec![0, 2, 4, 6]);
        assert_eq!(keep(&ring, 0.05).len(), 6);
    }

    #[test]
    fn long_ring_is_iterative() {
        let n = 200_000;
        let ring: Vec<Pt> = (0..n)
            .map(|i| {
                let t = i as f64 / n as f64 * std::f64::consts::TAU;
                [1000.0 * t.cos(), 1000.0 * t.sin()]
            })
            .collect();
        let k = keep(&ring, 0.01);
        assert!(k.len() > 100 && k.len() < n);
    }
}
