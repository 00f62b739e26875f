-- Valid polygons whose rings touch at a point encode, and decode valid at every arc tolerance up to
-- the grid step and as true arcs; the touch point is kept exactly.
-- Two parts meeting at a corner, and a hole touching its shell inside an edge (ST_IsValid: true).
SELECT ST_IsValid(g) AS input_valid, ST_IsValid(d) AS valid, ST_Equals(d, g) AS same_shape,
       ST_Intersects(ST_GeometryN(d, 1), ST_GeometryN(d, 2)) AS parts_still_touch
  FROM (SELECT g, ct_decode(ct_encode(g, 5, 0.4, 10)) d
          FROM (SELECT 'SRID=32633;MULTIPOLYGON(((0 0,100 0,100 100,0 100,0 0)),((100 100,200 100,200 200,100 200,100 100)))'::geometry g) s) t;
SELECT ST_IsValid(g) AS input_valid, ST_IsValid(d) AS valid, ST_NumInteriorRings(d) AS holes,
       ST_Intersects(ST_ExteriorRing(d), ST_InteriorRingN(d, 1)) AS hole_still_touches
  FROM (SELECT g, ct_decode(ct_encode(g, 5, 0.4, 10)) d
          FROM (SELECT 'SRID=32633;POLYGON((0 0,100 0,100 100,0 100,0 0),(50 0,60 20,40 20,50 0))'::geometry g) s) t;
-- What ST_MakeValid makes of a bow-tie (two triangles meeting at one point), and round shapes
-- touching: a disc and a disc-shaped hole touching a square's corner, valid however finely stroked.
SELECT ST_IsValid(ct_decode(ct_encode(ST_MakeValid('POLYGON((0 0,10 10,10 0,0 10,0 0))'::geometry), 0.5, 0.4, 1))) AS made_valid;
SELECT GeometryType(g) AS input, (SELECT bool_and(ST_IsValid(ct_decode(c, tol)))
          FROM unnest(ARRAY[1, 0.1, 0.01, 0.001]) tol) AS valid_at_every_tolerance,
       ST_IsValid(ST_CurveToLine(ct_decode_curved(c), 0.001, 1, 0)) AS curved_valid,
       ct_hausdorff(c, g) <= 10 AS within_max_error
  FROM (SELECT g, ct_encode(g, 5, 0.4, 10) c
          FROM (SELECT ST_Union(ST_Buffer('POINT(0 0)'::geometry, 100, 16),
                                'POLYGON((100 0,300 0,300 200,100 200,100 0))'::geometry) g) s) t;
-- A tiny max_error the stored format cannot hold is refused up front (22023, naming max_error and
-- its range); the smallest it can hold encodes and reads back.
SELECT ct_encode('POLYGON((0 0,1e-9 0,1e-9 1e-9,0 1e-9,0 0))'::geometry, 1e-12, 0.4, 1e-12);
SELECT ST_IsValid(ct_decode(ct_encode('POLYGON((0 0,1e-9 0,1e-9 1e-9,0 1e-9,0 0))'::geometry, 1e-9, 0.4, 1e-9))) AS tiny_valid;
SELECT sqlstate_of($$SELECT ct_encode('POLYGON((1e12 1e12,1.000001e12 1e12,1.000001e12 1.000001e12,1e12 1e12))'::geometry, 1e-3)$$);
