-- Bad input, geometry class: every geometry circletree cannot store, every invalid polygon, degenerate
-- rings and non-finite or extreme coordinates, given to each function that takes a geometry. Each
-- ends in a clean ERROR (the SQLSTATE, then the message; a missing hint would show as NO HINT),
-- never XX000 and never a crash. Geometries PostGIS itself cannot build are not ours to test.
CREATE TEMP TABLE g(class text, name text, geom geometry);
INSERT INTO g VALUES
 ('type', 'point', 'POINT(1 2)'),
 ('type', 'multipoint', 'MULTIPOINT((1 2),(3 4))'),
 ('type', 'linestring', 'LINESTRING(0 0,10 0,10 10)'),
 ('type', 'closed linestring', 'LINESTRING(0 0,10 0,10 10,0 0)'),
 ('type', 'multilinestring', 'MULTILINESTRING((0 0,1 1),(2 2,3 3))'),
 ('type', 'collection of polygons', 'GEOMETRYCOLLECTION(POLYGON((0 0,10 0,10 10,0 0)))'),
 ('type', 'empty collection', 'GEOMETRYCOLLECTION EMPTY'),
 ('type', 'circularstring', 'CIRCULARSTRING(0 0,1 1,2 0)'),
 ('type', 'curvepolygon', 'CURVEPOLYGON(CIRCULARSTRING(0 0,4 0,4 4,0 4,0 0))'),
 ('type', 'multisurface', 'MULTISURFACE(CURVEPOLYGON(CIRCULARSTRING(0 0,4 0,4 4,0 4,0 0)))'),
 ('type', 'triangle', 'TRIANGLE((0 0,10 0,0 10,0 0))'),
 ('type', 'tin', 'TIN(((0 0 0,0 1 0,1 1 0,0 0 0)))'),
 ('type', 'polyhedral surface', 'POLYHEDRALSURFACE(((0 0 0,0 1 0,1 1 0,0 0 0)))'),
 ('invalid', 'bow-tie', 'POLYGON((0 0,10 10,10 0,0 10,0 0))'),
 ('invalid', 'spike', 'POLYGON((0 0,10 0,10 10,5 10,5 20,5 10,0 10,0 0))'),
 ('invalid', 'hole outside the shell', 'POLYGON((0 0,10 0,10 10,0 10,0 0),(20 20,30 20,30 30,20 20))'),
 ('invalid', 'hole crossing the shell', 'POLYGON((0 0,10 0,10 10,0 10,0 0),(5 5,15 5,15 6,5 5))'),
 ('invalid', 'overlapping parts', 'MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0)),((5 5,15 5,15 15,5 15,5 5)))'),
 ('invalid', 'nested shells', 'MULTIPOLYGON(((0 0,10 0,10 10,0 10,0 0)),((2 2,4 2,4 4,2 2)))'),
 ('degenerate', 'zero-area ring', 'POLYGON((0 0,5 0,10 0,0 0))'),
 ('degenerate', 'repeated point ring', 'POLYGON((0 0,0 0,0 0,0 0))'),
 ('degenerate', 'two distinct points', 'POLYGON((0 0,1 1,1 1,0 0))'),
 ('coordinates', 'NaN', ST_MakePolygon(ST_MakeLine(ARRAY[ST_MakePoint(0, 0), ST_MakePoint('NaN', 0), ST_MakePoint(1, 1), ST_MakePoint(0, 0)]))),
 ('coordinates', 'Infinity', ST_MakePolygon(ST_MakeLine(ARRAY[ST_MakePoint(0, 0), ST_MakePoint('Infinity', 0), ST_MakePoint(1, 1), ST_MakePoint(0, 0)]))),
 ('coordinates', '1e300', 'POLYGON((0 0,1e300 0,1e300 1e300,0 0))'),
 ('coordinates', '1e-300', 'POLYGON((0 0,1e-300 0,1e-300 1e-300,0 0))'),
 ('coordinates', 'mixed 1e15 and 1e-15', 'POLYGON((1e15 1e15,1e15 1.000000000000001e15,1.0000000000001e15 1e15,1e15 1e15))');
-- each function that takes a geometry, with parameters that are themselves fine
SELECT class, name,
       outcome(format('SELECT ct_encode(%L::geometry, 5, 0.4, 10)', geom::text)) AS ct_encode,
       outcome(format('SELECT ct_encode_within(%L::geometry, 10)', geom::text)) AS ct_encode_within
FROM g ORDER BY class, name;
SELECT class, name,
       outcome(format('SELECT ct_sweep(%L::geometry, ARRAY[5], ARRAY[0.4], ARRAY[10])', geom::text)) AS ct_sweep,
       outcome(format('SELECT ct_hausdorff(%L::geometry, %L::geometry)', geom::text, geom::text)) AS ct_hausdorff
FROM g ORDER BY class, name;
-- the metrics compare a good value with a bad original
CREATE TEMP TABLE good AS SELECT ct_encode('POLYGON((0 0,100 0,100 100,0 100,0 0))'::geometry, 5, 0.4, 10) AS ct;
SELECT class, name,
       outcome(format('SELECT ct_sliver_error(%L::circletree, %L::geometry)', ct::text, geom::text)) AS ct_sliver_error,
       outcome(format('SELECT ct_hausdorff(%L::circletree, %L::geometry)', ct::text, geom::text)) AS ct_hausdorff_ct
FROM g, good ORDER BY class, name;
-- no geometry error of any function is internal or comes without a hint
SELECT count(*) AS outcomes,
       count(*) FILTER (WHERE o LIKE 'XX%' OR o LIKE '% NO HINT:%') AS internal_or_unhinted
FROM g, good, LATERAL (VALUES
  (outcome(format('SELECT ct_encode(%L::geometry, 5, 0.4, 10)', geom::text))),
  (outcome(format('SELECT ct_encode_within(%L::geometry, 10)', geom::text))),
  (outcome(format('SELECT ct_sweep(%L::geometry, ARRAY[5], ARRAY[0.4], ARRAY[10])', geom::text))),
  (outcome(format('SELECT ct_hausdorff(%L::geometry, %L::geometry)', geom::text, geom::text))),
  (outcome(format('SELECT ct_sliver_error(%L::circletree, %L::geometry)', ct::text, geom::text))),
  (outcome(format('SELECT ct_hausdorff(%L::circletree, %L::geometry)', ct::text, geom::text)))) AS t(o);
