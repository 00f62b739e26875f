-- The README's quick start, so the README cannot go stale.
CREATE TABLE readme_coast AS SELECT name, geom FROM coast WHERE name IN ('rarotonga', 'kapiti_island_linz');
SELECT name, pg_column_size(ct) < pg_column_size(geom) AS smaller, round(ct_storage_ratio(ct)::numeric, 3) AS ratio,
       ct_sliver_error(ct, geom) > 0 AS some_sliver, ct_hausdorff(ct, geom) <= 10 AS within_10m
  FROM (SELECT name, geom, ct_encode(geom, 5, 0.4, 10) AS ct FROM readme_coast) s ORDER BY name;
SELECT ST_IsValid(ct_decode(ct_encode(geom, 5, 0.4, 10))) FROM readme_coast ORDER BY name;
