-- Generated from README.md by scripts/readme_sql.sh (the README's tested SQL blocks); do not edit.
CREATE EXTENSION IF NOT EXISTS circletree CASCADE;   -- pulls in postgis
-- the fewest bytes within 10 m (continuous Hausdorff), always valid; and the paper's circles
SELECT name, pg_column_size(geom) AS geom_bytes,
       pg_column_size(ct_encode_within(geom, 10)) AS within_bytes,
       pg_column_size(ct_encode(geom, 5, 0.4, 10)) AS paper_bytes
  FROM coast WHERE name IN ('rarotonga', 'kapiti_island_linz') ORDER BY name;
SELECT name, round(ct_storage_ratio(ct)::numeric, 3) AS ratio,
       round(ct_sliver_ratio(ct, geom)::numeric, 5) AS sliver_ratio,
       ct_hausdorff(ct, geom) <= 10 AS within_10_m, ST_IsValid(ct_decode(ct)) AS valid
  FROM (SELECT name, geom, ct_encode_within(geom, 10) AS ct FROM coast
         WHERE name IN ('rarotonga', 'kapiti_island_linz')) s ORDER BY name;
SELECT name, ct_srid(ct) AS utm_srid, ST_SRID(ct_decode_geography(ct)::geometry) AS back_srid,
       ct_hausdorff(ct, ST_Transform(geom, ct_srid(ct))) <= 10 AS within_10_m
  FROM (SELECT name, geom, ct_encode_within(geom::geography, 10) AS ct
          FROM (SELECT name, ST_Transform(geom, 4326) AS geom FROM coast WHERE name = 'rarotonga') g) s;
CREATE TABLE coast_ct AS SELECT name, ct_encode_within(geom, 10) AS ct FROM coast;
CREATE INDEX coast_ct_idx ON coast_ct USING gist (ct);
SELECT c.name, ct_intersects(c.ct, ST_PointOnSurface(g.geom)) AS holds_a_point_inside,
       round(ct_distance(c.ct, ST_Translate(ST_PointOnSurface(g.geom), 1e5, 0))) > 0 AS far_point_is_away,
       round((ST_Area(c.ct::geometry) / ST_Area(g.geom))::numeric, 3) AS area_ratio
  FROM coast_ct c JOIN coast g USING (name) WHERE name = 'rarotonga';
DROP TABLE coast_ct;
