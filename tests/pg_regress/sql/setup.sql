-- Every regress file runs after this one, in the same database.
CREATE EXTENSION circletree CASCADE;
-- SQLSTATE and message of a statement, for error tests that must show the SQLSTATE.
CREATE FUNCTION sqlstate_of(q text) RETURNS text LANGUAGE plpgsql AS $$
BEGIN
  EXECUTE q;
  RETURN 'ok';
EXCEPTION WHEN OTHERS THEN
  RETURN SQLSTATE || ': ' || SQLERRM;
END $$;
CREATE TABLE poly(name text, source text, srid int, npoints int, wkt text);
\copy poly FROM PROGRAM 'gzip -dc tests/data/polygons.tsv.gz' WITH (FORMAT csv, DELIMITER E'\t', HEADER true, QUOTE E'\x01')
CREATE TABLE coast AS SELECT name, npoints, ST_GeomFromText(wkt, srid) AS geom FROM poly;
SELECT count(*), sum(npoints) FROM coast;
