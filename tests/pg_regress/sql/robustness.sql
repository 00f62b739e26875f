-- The robustness suites nobody on the project wrote: every Polygon and MultiPolygon of GEOS's and
-- JTS's XML validity and overlay tests (tests/data/robustness.tsv.gz, from scripts/robustness_suites.py;
-- sources and licences in tests/data/README.md). PostGIS decides which are valid.
-- Every valid one, with both encoders at 1% and 0.1% of its extent, is encoded valid, within its bound
-- and round-trips through text and bytea, or is refused because its rings come closer than the
-- finest grid its coordinates allow (the stated limit: clearance, magnitude, finest grid). Any
-- other refusal is listed. Every invalid one is refused with 22023 and a hint.
SET client_min_messages = warning;
CREATE TABLE robust (source text, file text, wkt text);
\copy robust FROM PROGRAM 'gzip -dc tests/data/robustness.tsv.gz' WITH (FORMAT csv, DELIMITER E'\t', HEADER true, QUOTE E'\x01')
CREATE FUNCTION pg_temp.geom(t text) RETURNS geometry LANGUAGE plpgsql AS $$
BEGIN RETURN ST_GeomFromText(t); EXCEPTION WHEN others THEN RETURN NULL; END $$;
ALTER TABLE robust ADD COLUMN id serial, ADD COLUMN g geometry;
UPDATE robust SET g = pg_temp.geom(wkt);
-- (a few are not WKT PostGIS reads: EMPTY rings inside a polygon)
SELECT source, count(*) AS polygons, count(*) FILTER (WHERE g IS NULL) AS unreadable,
       count(*) FILTER (WHERE ST_IsValid(g)) AS valid, count(*) FILTER (WHERE NOT ST_IsValid(g)) AS invalid
  FROM robust GROUP BY source ORDER BY source;
-- One encoder at one bound: the value, or the refusal's SQLSTATE, message and hint.
CREATE FUNCTION pg_temp.try(g geometry, encoder text, t float8,
    OUT ct circletree, OUT state text, OUT message text, OUT hint text) LANGUAGE plpgsql AS $$
BEGIN
  IF encoder = 'ct_encode' THEN ct := ct_encode(g, t, 0.4, t);
  ELSE ct := ct_encode_within(g, t);
  END IF;
EXCEPTION WHEN others THEN
  GET STACKED DIAGNOSTICS state = RETURNED_SQLSTATE, message = MESSAGE_TEXT, hint = PG_EXCEPTION_HINT;
END $$;
CREATE TABLE tried AS
SELECT r.id, e.encoder, f.fraction, t.*, r.g,
       f.fraction * greatest(ST_XMax(r.g) - ST_XMin(r.g), ST_YMax(r.g) - ST_YMin(r.g)) AS bound
  FROM robust r, (VALUES ('ct_encode'), ('ct_encode_within')) e(encoder), (VALUES (0.01), (0.001)) f(fraction),
       pg_temp.try(r.g, e.encoder, f.fraction * greatest(ST_XMax(r.g) - ST_XMin(r.g), ST_YMax(r.g) - ST_YMin(r.g))) t
 WHERE ST_IsValid(r.g);
SELECT encoder, fraction, count(*) AS valid_polygons,
       count(*) FILTER (WHERE ct IS NOT NULL) AS encoded,
       count(*) FILTER (WHERE ct IS NOT NULL AND ST_IsValid(ct_decode(ct)) AND ct_hausdorff(ct, g) <= bound
                          AND ct::text::circletree::bytea = ct::bytea AND ct::bytea::circletree::bytea = ct::bytea)
         AS valid_within_and_round_trips,
       count(*) FILTER (WHERE state = '22023' AND message LIKE 'could not encode the polygon: its rings come within % of each other (its minimum clearance), and coordinates as large as % allow no grid finer than %'
                          AND hint <> '') AS beyond_the_coordinates_precision,
       count(*) FILTER (WHERE ct IS NULL AND message NOT LIKE 'could not encode the polygon: its rings come within %') AS other_refusals
  FROM tried GROUP BY encoder, fraction ORDER BY encoder, fraction DESC;
-- (none)
SELECT id, encoder, fraction, state, message FROM tried
 WHERE ct IS NULL AND message NOT LIKE 'could not encode the polygon: its rings come within %' ORDER BY id, encoder, fraction;
-- A refusal names a clearance below twice the finest grid, which is what the coordinates' magnitude
-- allows (2^-50 of it, and not below the format's 1e-12); PostGIS's ST_MinimumClearance agrees, to
-- within what a double holds at that magnitude.
SELECT count(*) AS refusals,
       bool_and(c < 2 * finest AND finest >= greatest(magnitude * 2 ^ (-50), 1e-12) AND finest < 5 * greatest(magnitude * 2 ^ (-50), 1e-12))
         AS clearance_below_the_finest_grid,
       bool_and(abs(c - ST_MinimumClearance(g)) <= magnitude * 2 ^ (-50)) AS clearance_is_postgis_s
  FROM (SELECT g, m[1]::float8 AS c, m[2]::float8 AS magnitude, m[3]::float8 AS finest
          FROM tried, regexp_match(message, 'within (\S+) of each other .* as large as (\S+) allow no grid finer than (\S+),') m
         WHERE ct IS NULL) r;
-- Every invalid one: 22023 with a hint, from both encoders.
SELECT count(*) AS invalid_tries, count(*) FILTER (WHERE t.state = '22023' AND t.hint <> '') AS refused_22023_with_hint
  FROM robust r, (VALUES ('ct_encode'), ('ct_encode_within')) e(encoder), pg_temp.try(r.g, e.encoder, 1) t
 WHERE NOT ST_IsValid(r.g);
DROP TABLE tried;
DROP TABLE robust;
RESET client_min_messages;
