-- Memory budget (issue 9 item 4): an encode whose estimated peak exceeds
-- circletree.max_encode_memory is refused before it allocates (54000, with a hint), not left to
-- the out-of-memory killer; only a superuser may change the budget.
SELECT ct_srid(ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 1, 0.4, 1)) AS loads_the_library;
SHOW circletree.max_encode_memory;
CREATE TEMP TABLE star AS
SELECT n, ST_MakePolygon(ST_MakeLine(array_agg(ST_MakePoint(r * cos(t), r * sin(t)) ORDER BY i) || ST_MakePoint(100000 + 1000, 0))) AS geom
  FROM (SELECT n, i, 2 * pi() * i / n AS t, 100000 + 1000 * cos(37 * 2 * pi() * i / n) AS r
          FROM (VALUES (20000), (200000)) v(n), generate_series(0, n - 1) i) s
 GROUP BY n;
SELECT n, ST_NPoints(geom), ST_IsValid(geom) FROM star ORDER BY n;
SET circletree.max_encode_memory = '16MB';
SELECT n, outcome(format('SELECT ct_encode(geom, 5, 0.4, 10) FROM star WHERE n = %s', n)) AS ct_encode,
       outcome(format('SELECT ct_encode_within(geom, 10) FROM star WHERE n = %s', n)) AS ct_encode_within,
       outcome(format('SELECT ct_encode(ST_Transform(ST_SetSRID(geom, 32760), 4326)::geography, 5, 0.4, 10) FROM star WHERE n = %s', n)) AS geography
  FROM star ORDER BY n;
RESET circletree.max_encode_memory;
SHOW circletree.max_encode_memory;
-- a role without superuser can neither raise nor lower it
CREATE ROLE ct_memory_user;
SET ROLE ct_memory_user;
SELECT outcome('SET circletree.max_encode_memory = ''64GB''') AS set_by_non_superuser;
RESET ROLE;
DROP ROLE ct_memory_user;
-- Decoding is bounded by what one value can hold: a value of 30,000 discs of radius 1,000,000
-- (text input, so anyone can send it) would stroke to about 67 million points at its grid, so
-- ct_decode, ct_svg and the metrics refuse it with 54000 before building anything; coarser, it decodes.
CREATE TEMP TABLE discs AS
SELECT format('CIRCLETREE(version=2;grid=1;min_radius=5;overlap=0.4;dp_tolerance=NULL;max_error=5;vertices=5;wkb_bytes=93;repaired=0;bbox=(0 0,2000000 2000000);MULTIPOLYGON(%s))',
              string_agg('((1000000 1000000 1000000))', ','))::circletree AS ct
  FROM generate_series(1, 30000);
SELECT ct_ncircles(ct) FROM discs;
SELECT outcome('SELECT ct_decode(ct) FROM discs') AS ct_decode,
       outcome('SELECT ct_svg(ct) FROM discs') AS ct_svg,
       outcome('SELECT ct_hausdorff(ct, ''POLYGON((0 0,1 0,1 1,0 0))''::geometry) FROM discs') AS ct_hausdorff,
       outcome('SELECT ct_sliver_error(ct, ''POLYGON((0 0,1 0,1 1,0 0))''::geometry) FROM discs') AS ct_sliver_error;
SELECT ST_NPoints(ct_decode(ct, 100000)) FROM discs;
