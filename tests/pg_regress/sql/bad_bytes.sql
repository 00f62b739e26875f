-- Bad input, bytes class: stored or received bytes that are truncated, extended, bit-flipped or
-- claim impossible lengths, through bytea::circletree and binary COPY (circletree_recv). Each is
-- 22P03 with a hint, or (for a flip that spells another valid value) a value that reads back to the
-- same bytes; never XX000, never a crash.
CREATE TEMP TABLE b(name text, bytes bytea);
INSERT INTO b SELECT 'v1 polygon', ('SRID=32760;CIRCLETREE(grid=0.5;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,10 10);POLYGON((5 5 5,8 5 0,8 8 -1)))'::circletree)::bytea;
INSERT INTO b SELECT 'v2 multipolygon', ('SRID=0;CIRCLETREE(version=2;grid=0.01;min_radius=1;overlap=0;dp_tolerance=2.5;max_error=2.5;vertices=12;wkb_bytes=200;repaired=1;bbox=(-1.5 0,3 4.25);MULTIPOLYGON(((0 0 0,3 0 0,3 4.25 -0.5)),((-1.5 1 0,-1 1 0,-1 2 1.25),(1 1 0,1.5 1 0,1 1.5 0))))'::circletree)::bytea;
INSERT INTO b SELECT 'v2 rarotonga', ct_encode(geom, 50, 0.4, 100)::bytea FROM coast WHERE name = 'rarotonga';
SELECT name, length(bytes) FROM b ORDER BY name;
-- every proper prefix
SELECT name, count(*) AS prefixes, string_agg(DISTINCT split_part(o, ':', 1), ', ') AS outcomes
FROM b, generate_series(0, length(bytes) - 1) AS i,
     LATERAL outcome(format('SELECT %L::bytea::circletree', substr(bytes, 1, i))) AS o
GROUP BY name ORDER BY name;
-- one byte appended, each of 0, 1, 127, 255
SELECT name, string_agg(DISTINCT split_part(o, ':', 1), ', ') AS outcomes
FROM b, unnest(ARRAY['\x00', '\x01', '\x7f', '\xff']::bytea[]) AS x,
     LATERAL outcome(format('SELECT %L::bytea::circletree', bytes || x)) AS o
GROUP BY name ORDER BY name;
-- every bit flipped, one at a time
SELECT name, count(*) AS flips, count(*) FILTER (WHERE o = 'ok') AS still_a_value,
       string_agg(DISTINCT split_part(o, ':', 1), ', ') AS outcomes,
       bool_and(o <> 'ok' OR (SELECT f::circletree::bytea = f)) AS accepted_read_back
FROM b, generate_series(0, 8 * length(bytes) - 1) AS k,
     LATERAL (SELECT set_bit(bytes, k, 1 - get_bit(bytes, k)) AS f) AS m,
     LATERAL outcome(format('SELECT %L::bytea::circletree', f)) AS o
GROUP BY name ORDER BY name;
-- impossible lengths: counts of 2^32, 2^63 and more rings, parts and circles than bytes
SELECT outcome(format('SELECT %L::bytea::circletree', x)) FROM (VALUES
 ('\x01030002000a0008ff000a000000000100000000018080808010'::bytea),
 ('\x01030002000a0008ff000a00000000ffffffffffffffffff01'::bytea),
 ('\x0206000a000a0008ff000a0000000080808080100000000000'::bytea),
 ('\x'::bytea), ('\x00'::bytea), ('\x0903'::bytea)) AS t(x);
-- binary COPY (circletree_recv): an intact file loads; the same file with its value's version byte
-- changed, or a byte inside the value's circles changed, is refused as the cast refuses it
CREATE TEMP TABLE back(ct circletree);
COPY (SELECT bytes::circletree FROM b WHERE name = 'v2 rarotonga') TO '/tmp/circletree_regress_bad.bin' WITH (FORMAT binary);
SELECT outcome($$COPY back FROM '/tmp/circletree_regress_bad.bin' WITH (FORMAT binary)$$) AS intact;
-- the file: 19-byte header, then per row a field count (2 bytes) and the datum's length (4)
CREATE TEMP TABLE damaged AS
  SELECT at, lo_from_bytea(0, set_byte(f, at, CASE WHEN at = 25 THEN 9 ELSE 255 - get_byte(f, at) END)) AS o
    FROM (SELECT pg_read_binary_file('/tmp/circletree_regress_bad.bin') AS f) AS file, unnest(ARRAY[25, 60]) AS at;
SELECT at, lo_export(o, '/tmp/circletree_regress_bad_' || at || '.bin') AS written FROM damaged ORDER BY at;
SELECT at, outcome(format($$COPY back FROM '/tmp/circletree_regress_bad_%s.bin' WITH (FORMAT binary)$$, at)) AS damaged
  FROM damaged ORDER BY at;
SELECT count(lo_unlink(o)) AS removed FROM damaged;
SELECT count(*) AS loaded FROM back;
SELECT count(*) FILTER (WHERE o LIKE 'XX%' OR o LIKE '% NO HINT:%') AS internal_or_unhinted
FROM b, generate_series(0, length(bytes) - 1) AS i,
     LATERAL outcome(format('SELECT %L::bytea::circletree', substr(bytes, 1, i))) AS o;
