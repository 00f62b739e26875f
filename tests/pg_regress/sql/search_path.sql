-- A hostile search_path (issue 9, the CVE-2018-1058 class): a schema ahead of PostGIS's defines
-- functions with PostGIS's and circletree's names. The wrappers call everything schema-qualified, so
-- their results do not change.
CREATE SCHEMA evil;
CREATE FUNCTION evil.st_srid(geometry) RETURNS int LANGUAGE sql AS $$ SELECT 4326 $$;
CREATE FUNCTION evil.st_isvalid(geometry) RETURNS bool LANGUAGE sql AS $$ SELECT true $$;
CREATE FUNCTION evil.st_asbinary(geometry) RETURNS bytea LANGUAGE sql
    AS $$ SELECT public.ST_AsBinary(public.ST_Buffer($1, 1000)) $$;
CREATE FUNCTION evil.st_geomfromewkb(bytea) RETURNS geometry LANGUAGE sql
    AS $$ SELECT 'POINT(0 0)'::geometry $$;
CREATE FUNCTION evil.st_area(geometry) RETURNS float8 LANGUAGE sql AS $$ SELECT 1::float8 $$;
CREATE FUNCTION evil.pg_column_size(circletree) RETURNS int LANGUAGE sql AS $$ SELECT 1 $$;
CREATE TABLE sp AS
SELECT name, geom, ct_encode(geom, 5, 0.4, 10) AS ct FROM coast WHERE name IN ('lake_tahoe', 'kapiti_island_linz');
CREATE TABLE sp_expected AS
SELECT name, ct::bytea AS bytes, ST_AsBinary(ct_decode(ct)) AS decoded, ct_sliver_ratio(ct, geom) AS sliver,
       ct_storage_ratio(ct, geom) AS ratio, ct_hausdorff(ct, geom) AS h
  FROM sp;
SET search_path = evil, public, pg_catalog;
-- what the evil functions would give if called
SELECT st_srid('POINT(1 1)'::geometry) AS evil_srid, st_area('POINT(1 1)'::geometry) AS evil_area,
       pg_column_size(ct) AS evil_size FROM sp LIMIT 1;
-- every wrapper gives what it gave before
SELECT s.name,
       ct_encode(s.geom, 5, 0.4, 10)::bytea = e.bytes AS same_encoding,
       ct_srid(ct_encode(s.geom, 5, 0.4, 10)) AS srid,
       ct_encode_within(s.geom, 10) IS NOT NULL AS within_encodes,
       public.ST_AsBinary(ct_decode(s.ct)) = e.decoded AS same_decode,
       public.ST_AsBinary(ct_decode(s.ct, NULL)) = e.decoded AS same_decode_tol,
       public.ST_GeometryType(ct_decode_curved(s.ct)) AS curved,
       ct_sliver_ratio(s.ct, s.geom) = e.sliver AS same_sliver,
       ct_storage_ratio(s.ct, s.geom) = e.ratio AS same_ratio,
       ct_hausdorff(s.ct, s.geom) = e.h AS same_hausdorff
  FROM sp s JOIN sp_expected e USING (name) ORDER BY s.name;
-- an invalid polygon is still refused: the evil st_isvalid is not the one asked
SELECT sqlstate_of('SELECT ct_encode(''POLYGON((0 0,10 10,10 0,0 10,0 0))''::geometry, 1)');
RESET search_path;
DROP SCHEMA evil CASCADE;
DROP TABLE sp, sp_expected;
