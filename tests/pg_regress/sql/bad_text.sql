-- Bad input, text class: every prefix of valid text forms, every single character replaced, and
-- hand-made malformed values. Each is 22P02 with a hint, or, for a replacement that spells a valid
-- value (another number, a blank between tokens), accepted: its printed text reads back to its bytes.
CREATE TEMP TABLE t(name text, txt text);
INSERT INTO t VALUES
 ('polygon', 'SRID=32760;CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5)))'),
 ('multipolygon', 'SRID=0;CIRCLETREE(version=2;grid=0.01;min_radius=1;overlap=0;dp_tolerance=2.5;max_error=2.5;vertices=12;wkb_bytes=200;repaired=1;bbox=(-1.5 0,3 4.25);MULTIPOLYGON(((0 0 0,3 0 0,3 4.25 -0.5)),((-1.5 1 0,-1 1 0,-1 2 1.25),(1 1 0,1.5 1 0,1 1.5 0))))'),
 ('empty', 'SRID=4326;CIRCLETREE(version=2;grid=1;min_radius=1;overlap=0.4;dp_tolerance=NULL;max_error=1;vertices=0;wkb_bytes=9;repaired=0;POLYGON EMPTY)');
SELECT name, txt::circletree::text = txt AS reads_back FROM t ORDER BY name;
-- every proper prefix
SELECT name, count(*) AS prefixes, string_agg(DISTINCT split_part(o, ':', 1), ', ') AS outcomes
FROM t, generate_series(0, length(txt) - 1) AS i,
     LATERAL outcome(format('SELECT %L::circletree', left(txt, i))) AS o
GROUP BY name ORDER BY name;
-- every character replaced by each of a few others
SELECT name, count(*) AS variants, string_agg(DISTINCT split_part(o, ':', 1), ', ') AS outcomes,
       bool_and(o <> 'ok' OR (SELECT v::circletree::text::circletree::bytea = v::circletree::bytea)) AS accepted_read_back
FROM t, generate_series(1, length(txt)) AS i, unnest(ARRAY['9', '-', ' ', ';', '(', 'x', 'e', '.']) AS c,
     LATERAL (SELECT overlay(txt PLACING c FROM i FOR 1) AS v) AS m,
     LATERAL outcome(format('SELECT %L::circletree', v)) AS o
GROUP BY name ORDER BY name;
-- hand-made: numbers off the grid or out of range, unknown versions and keywords, huge counts
SELECT outcome(q) FROM (VALUES
 ('SELECT ''CIRCLETREE(version=9;grid=1;''::circletree'),
 ('SELECT ''CIRCLETREE(version=1;grid=1;''::circletree'),
 ('SELECT ''SRID=99999999999;CIRCLETREE(grid=1;''::circletree'),
 ('SELECT ''CIRCLETREE(grid=1e400;''::circletree'),
 ('SELECT ''CIRCLETREE(grid=NaN;''::circletree'),
 ('SELECT ''CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=99999999999999999999999;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5)))''::circletree'),
 ('SELECT ''CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,1e300 10);POLYGON((5 5 5)))''::circletree'),
 ('SELECT ''CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5e300)))''::circletree'),
 ('SELECT ''CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5)),(1 1 1))''::circletree'),
 ('SELECT ''CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON(()))''::circletree'),
 ('SELECT ''CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);CURVEPOLYGON((5 5 5)))''::circletree'),
 ('SELECT E''CIRCLETREE(grid=0.5;\\u00e9''::circletree')) AS q(q);
SELECT count(*) FILTER (WHERE o LIKE 'XX%' OR o LIKE '% NO HINT:%') AS internal_or_unhinted
FROM t, generate_series(0, length(txt) - 1) AS i, LATERAL outcome(format('SELECT %L::circletree', left(txt, i))) AS o;
