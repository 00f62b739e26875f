-- Find by location without decoding (issue 10): ct_envelope(ct) reads the stored bounding box from
-- the header (no circle is decoded), widened by max_error, so it holds both the original and
-- ct_decode(ct); an expression GiST index on it answers && queries.
-- one table per SRID, as users keep them (&& compares boxes whatever their SRID): the polygons in
-- UTM zone 60S
CREATE TABLE env AS SELECT name, geom, ct_encode_within(geom, 25) AS ct FROM coast WHERE ST_SRID(geom) = 32760;
-- it holds both; and it is tight: at most max_error plus one grid step beyond the original's box
SELECT count(*) AS polygons,
       count(*) FILTER (WHERE ST_Contains(ct_envelope(ct), ct_decode(ct))) AS holds_decoded,
       count(*) FILTER (WHERE ST_Contains(ct_envelope(ct), geom)) AS holds_original,
       count(*) FILTER (WHERE ST_SRID(ct_envelope(ct)) = ST_SRID(geom)) AS same_srid,
       count(*) FILTER (WHERE ST_XMin(e) >= ST_XMin(geom) - 25 - g AND ST_YMin(e) >= ST_YMin(geom) - 25 - g
                          AND ST_XMax(e) <= ST_XMax(geom) + 25 + g AND ST_YMax(e) <= ST_YMax(geom) + 25 + g) AS tight
  FROM (SELECT *, ct_envelope(ct) AS e, (ct_summary(ct)->>'grid')::float8 AS g FROM env) s;
CREATE INDEX env_envelope ON env USING gist (ct_envelope(ct));
ANALYZE env;
-- a box over Rangitoto Island and the west end of Waiheke Island (UTM 60S)
\set box 'ST_MakeEnvelope(305000, 5925000, 321000, 5930000, 32760)'
SET enable_seqscan = off;
EXPLAIN (COSTS OFF) SELECT name FROM env WHERE ct_envelope(ct) && :box;
SELECT string_agg(name, ',' ORDER BY name) AS found_by_index FROM env WHERE ct_envelope(ct) && :box;
RESET enable_seqscan;
SET enable_indexscan = off;
SET enable_bitmapscan = off;
SELECT string_agg(name, ',' ORDER BY name) AS found_by_seqscan FROM env WHERE ct_envelope(ct) && :box;
RESET enable_indexscan;
RESET enable_bitmapscan;
-- the same rows as the decoded polygons would give (the envelope holds them)
SELECT string_agg(name, ',' ORDER BY name) AS decoded_intersect FROM env
 WHERE ST_Intersects(ct_decode(ct), :box);
-- empty in, empty out; NULL in, NULL out; bytes cut after the header still have their envelope
-- (only the header is read), other corrupt bytes are refused with 22P03
SELECT ST_AsText(ct_envelope(ct_encode_within('POLYGON EMPTY'::geometry, 1))) AS empty,
       ct_envelope(NULL) IS NULL AS null_in;
SELECT sqlstate_of('SELECT ct_envelope(''\x0203''::bytea::circletree)');
DROP TABLE env;
