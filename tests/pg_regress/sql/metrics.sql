-- Storage ratio, sliver area and Hausdorff: agree with PostGIS as stated.
CREATE TABLE m AS SELECT name, geom, ct_encode(geom, 25, 0.4, 50) AS ct FROM coast;
-- ct_storage_ratio(ct) is ct_memsize over the recorded WKB size; the two-argument form uses pg_column_size
SELECT count(*) FILTER (WHERE abs(ct_storage_ratio(ct) - ct_memsize(ct)::float8 / octet_length(ST_AsBinary(geom))) < 1e-12) AS ratio_ok,
       count(*) FILTER (WHERE abs(ct_storage_ratio(ct, geom) - pg_column_size(ct)::float8 / pg_column_size(geom)) < 1e-12) AS column_ratio_ok,
       count(*) AS polygons
  FROM m;
-- sliver area: within 1% (or 1 square unit) of PostGIS's ST_Area(ST_SymDifference(...))
SELECT count(*) FILTER (WHERE abs(ct_sliver_error(ct, geom) - ST_Area(ST_SymDifference(geom, ct_decode(ct, (ct_summary(ct)->>'grid')::float8 / 100))))
                              <= greatest(1, 0.01 * ST_Area(ST_SymDifference(geom, ct_decode(ct, (ct_summary(ct)->>'grid')::float8 / 100))))) AS sliver_agrees,
       count(*) FILTER (WHERE abs(ct_sliver_ratio(ct, geom) - ct_sliver_error(ct, geom) / ST_Area(geom)) < 1e-12) AS sliver_ratio_ok
  FROM m;
-- continuous Hausdorff is never below PostGIS's discrete one (which is quadratic: polygons of at
-- most 2,000 vertices)
SELECT count(*) AS polygons,
       count(*) FILTER (WHERE ct_hausdorff(ct, geom) + 1e-6 >= ST_HausdorffDistance(ct_decode(ct, (ct_summary(ct)->>'grid')::float8 / 100), geom)) AS not_below
  FROM m WHERE ST_NPoints(geom) <= 2000;
-- ct_hausdorff(geometry, geometry): the same continuous measure between any two polygons.
-- A square against itself, and against the square with one edge pushed out by 2 in its middle
-- (a tent): the farthest point is the tent's apex, 2 away. (Literals need ::geometry: the
-- circletree overload makes an untyped first argument ambiguous.)
SELECT ct_hausdorff('POLYGON((0 0,10 0,10 10,0 10,0 0))'::geometry, 'POLYGON((0 0,10 0,10 10,0 10,0 0))'::geometry) AS same,
       round(ct_hausdorff('POLYGON((0 0,10 0,10 10,0 10,0 0))'::geometry, 'POLYGON((0 0,5 -2,10 0,10 10,0 10,0 0))'::geometry)::numeric, 9) AS tent,
       -- both ways: the dent's vertex (5 9) is 1 from the square (the square's top edge is only
       -- 5/sqrt(26) = 0.98 from the dented one)
       round(ct_hausdorff('POLYGON((0 0,10 0,10 10,0 10,0 0))'::geometry, 'POLYGON((0 0,10 0,10 10,5 9,0 10,0 0))'::geometry)::numeric, 9) AS dent;
-- on ST_Simplify results: never below PostGIS's discrete measure (vertices only)
SELECT count(*) AS polygons,
       count(*) FILTER (WHERE ct_hausdorff(s, geom) + 1e-6 >= ST_HausdorffDistance(s, geom)) AS not_below
  FROM (SELECT geom, ST_Simplify(geom, 50, true) AS s FROM coast WHERE ST_NPoints(geom) <= 2000) x;
SELECT sqlstate_of($$SELECT ct_hausdorff('LINESTRING(0 0,1 1)'::geometry, 'POLYGON((0 0,1 0,1 1,0 0))'::geometry)$$) AS linestring;
-- the paper's experiment on Kapiti Island, a slice of it (ct_sweep with its default arrays runs all 150)
SELECT min_radius, overlap, dp_tolerance, circles, internal, external, zero, added_by_repair, bytes, valid,
       hausdorff <= greatest(min_radius, coalesce(dp_tolerance, 0)) AS within_bound
  FROM ct_sweep((SELECT geom FROM coast WHERE name = 'kapiti_island_linz'), '{5,25}', '{0,0.9}', '{NULL,10}');
