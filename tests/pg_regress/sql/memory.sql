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
