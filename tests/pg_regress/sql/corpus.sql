-- The codec's done criteria on every real polygon, at the three settings of the issue, checked by
-- PostGIS itself: valid, same SRID, same number of parts, Hausdorff distance within max_error
-- (our continuous ct_hausdorff on all of them; PostGIS's discrete ST_HausdorffDistance, which is
-- quadratic, on the 41 polygons of at most 5,000 vertices).
CREATE TABLE enc AS
SELECT c.name, p.min_radius, p.dp, greatest(p.min_radius, p.dp) AS max_error, c.geom,
       ct_encode(c.geom, p.min_radius, 0.4, p.dp) AS ct
  FROM coast c, (VALUES (5.0, 10.0), (25, 50), (100, 200)) p(min_radius, dp);
CREATE TABLE dec AS SELECT *, ct_decode(ct) AS d FROM enc;
SELECT min_radius, dp, count(*) AS polygons,
       count(*) FILTER (WHERE ST_IsValid(d)) AS valid,
       count(*) FILTER (WHERE ST_SRID(d) = ST_SRID(geom)) AS same_srid,
       count(*) FILTER (WHERE ST_NumGeometries(d) = ST_NumGeometries(geom)) AS same_parts,
       count(*) FILTER (WHERE ct_hausdorff(ct, geom) <= max_error) AS hausdorff_ok,
       count(*) FILTER (WHERE ST_NPoints(geom) <= 5000 AND ST_HausdorffDistance(d, geom) <= max_error) AS postgis_hausdorff_ok,
       count(*) FILTER (WHERE ST_NPoints(geom) <= 5000 AND ST_HausdorffDistance(d, geom) <= ct_hausdorff(d, geom) + 1e-6) AS discrete_not_above
  FROM dec GROUP BY 1, 2 ORDER BY 1;
-- smaller than the WKB everywhere, and much smaller at coarser settings
SELECT min_radius, dp, count(*) FILTER (WHERE ct_memsize(ct) < octet_length(ST_AsBinary(geom))) AS smaller,
       round(sum(ct_memsize(ct))::numeric / sum(octet_length(ST_AsBinary(geom))), 2) AS ratio_band
  FROM enc GROUP BY 1, 2 ORDER BY 1;
-- the stored WKB size is the real one
SELECT count(*) FILTER (WHERE (ct_summary(ct)->>'original_wkb_bytes')::int = octet_length(ST_AsBinary(geom))) AS wkb_size_recorded,
       count(*) FILTER (WHERE (ct_summary(ct)->>'original_vertices')::int = ST_NPoints(geom)) AS vertices_recorded
  FROM enc;
