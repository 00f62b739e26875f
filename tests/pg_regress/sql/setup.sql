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
-- What a statement ends in, for the bad-input files: ok, or SQLSTATE, whether a hint came with it,
-- and the message. An input error must never be XX000 (internal) and must carry a hint.
CREATE FUNCTION outcome(q text) RETURNS text LANGUAGE plpgsql AS $$
DECLARE st text; msg text; hint text;
BEGIN
  EXECUTE q;
  RETURN 'ok';
EXCEPTION WHEN OTHERS THEN
  GET STACKED DIAGNOSTICS st = RETURNED_SQLSTATE, msg = MESSAGE_TEXT, hint = PG_EXCEPTION_HINT;
  RETURN st || CASE WHEN coalesce(hint, '') = '' THEN ' NO HINT' ELSE '' END || ': ' || msg;
END $$;
CREATE TABLE poly(name text, source text, srid int, npoints int, wkt text);
\copy poly FROM PROGRAM 'gzip -dc tests/data/polygons.tsv.gz' WITH (FORMAT csv, DELIMITER E'\t', HEADER true, QUOTE E'\x01')
CREATE TABLE coast AS SELECT name, npoints, ST_GeomFromText(wkt, srid) AS geom FROM poly;
SELECT count(*), sum(npoints) FROM coast;
