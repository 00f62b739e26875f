-- The circletree type: text, bytea and binary round trips, equality, and every input error.
CREATE TABLE v(id int, ct circletree);
INSERT INTO v VALUES
 (1, 'SRID=32760;CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5)))'),
 (2, 'srid=0; circletree( grid=0.01; min_radius=1; overlap=0; dp_tolerance=2.5; max_error=2.5; vertices=12; wkb_bytes=200; repaired=1; bbox=(-1.5 0, 3 4.25); MULTIPOLYGON(((0 0 0, 3 0 0, 3 4.25 -0.5)), ((-1.5 1 0, -1 1 0, -1 2 1.25), (1 1 0, 1.5 1 0, 1 1.5 0)))) '),
 (3, 'SRID=4326;CIRCLETREE(grid=1;min_radius=1;overlap=0.4;dp_tolerance=NULL;max_error=1;vertices=0;wkb_bytes=9;repaired=0;POLYGON EMPTY)');
INSERT INTO v SELECT 4, ct_encode(geom, 5, 0.4, 10) FROM coast WHERE name = 'rarotonga';
-- text: canonical form, and text -> value gives the same bytes
SELECT id, ct::text FROM v WHERE id < 4 ORDER BY id;
SELECT id, ct::text::circletree = ct AS same, ct::text::circletree::bytea = ct::bytea AS same_bytes FROM v ORDER BY id;
-- bytea: the stored bytes, validated on the way back
SELECT id, ct::bytea FROM v WHERE id < 4 ORDER BY id;
SELECT id, ct::bytea::circletree = ct AS same FROM v ORDER BY id;
-- binary COPY uses circletree_send / circletree_recv
COPY (SELECT id, ct FROM v) TO '/tmp/circletree_regress_copy.bin' WITH (FORMAT binary);
CREATE TABLE v2(id int, ct circletree);
COPY v2 FROM '/tmp/circletree_regress_copy.bin' WITH (FORMAT binary);
SELECT count(*) AS copied, bool_and(v.ct = v2.ct) AS all_equal FROM v JOIN v2 USING (id);
-- = and <>
SELECT a.id, b.id, a.ct = b.ct AS eq, a.ct <> b.ct AS ne FROM v a, v b WHERE a.id <= 2 AND b.id <= 2 ORDER BY 1, 2;
-- storage: our own bytes, not compressed
SELECT typstorage, typlen FROM pg_type WHERE typname = 'circletree';
-- text errors: 22P02, naming what was expected and where
SELECT 'CIRCLETREE(grid=x;'::circletree;
SELECT sqlstate_of($$SELECT 'POINT(1 2)'::circletree$$);
SELECT sqlstate_of($$SELECT 'SRID=abc;CIRCLETREE('::circletree$$);
SELECT sqlstate_of($$SELECT 'CIRCLETREE(grid=0;'::circletree$$);
SELECT sqlstate_of($$SELECT 'CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5.25 5 5)))'::circletree$$);
SELECT sqlstate_of($$SELECT 'CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5))) trailing'::circletree$$);
SELECT sqlstate_of($$SELECT 'CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 0,6 6 0)))'::circletree$$);
SELECT sqlstate_of($$SELECT 'CIRCLETREE(grid=0.5;min_radius=5;overlap=1.5;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5)))'::circletree$$);
SELECT sqlstate_of($$SELECT 'CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;POLYGON((5 5 5)))'::circletree$$);
-- corrupt bytes: 22P03, never an internal error, never a crash
SELECT '\x0903'::bytea::circletree;
SELECT sqlstate_of($$SELECT ''::bytea::circletree$$);
SELECT sqlstate_of($$SELECT '\x01'::bytea::circletree$$);
SELECT sqlstate_of($$SELECT '\x0104'::bytea::circletree$$);
-- a polygon whose one ring claims 2^32 circles: refused before any allocation
SELECT sqlstate_of($$SELECT '\x01030002000a0008ff000a000000000100000000018080808010'::bytea::circletree$$);
-- a valid value with one byte more, one byte less, one byte changed
SELECT sqlstate_of(format('SELECT %L::bytea::circletree', (SELECT ct::bytea || '\x00'::bytea FROM v WHERE id = 1)));
SELECT sqlstate_of(format('SELECT %L::bytea::circletree', (SELECT substring(ct::bytea from 1 for length(ct::bytea) - 1) FROM v WHERE id = 1)));
SELECT sqlstate_of(format('SELECT %L::bytea::circletree', (SELECT set_byte(ct::bytea, 1, 7) FROM v WHERE id = 1)));
-- every truncation of a real value is refused cleanly
SELECT count(*) AS truncations, count(*) FILTER (WHERE r LIKE '22P03:%') AS refused_22p03
  FROM v, generate_series(0, length(ct::bytea) - 1) k,
       LATERAL (SELECT sqlstate_of(format('SELECT %L::bytea::circletree', substring(ct::bytea from 1 for k)))) s(r)
 WHERE id = 4;
