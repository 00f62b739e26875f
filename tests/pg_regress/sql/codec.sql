-- ct_encode / ct_decode / ct_decode_curved on hand-made shapes with known answers, and every error.
-- A disc drawn by ST_Buffer(point, 100, 8) comes back as one circle.
SELECT ct_ncircles(c), (ct_summary(c)->>'internal')::int AS internal, ct_summary(c)->>'grid' AS grid,
       ST_IsValid(ct_decode(c)) AS valid, ST_SRID(ct_decode(c)) AS srid,
       round(ST_HausdorffDistance(ct_decode(c), g)::numeric, 1) AS hausdorff_vertices,
       round(ct_hausdorff(c, g)::numeric, 1) AS hausdorff_continuous
  FROM (SELECT g, ct_encode(g, 5) AS c FROM (SELECT ST_Buffer(ST_SetSRID(ST_MakePoint(500000, 6000000), 32760), 100, 8) g) s) t;
-- A square comes back as its four corners, exactly.
SELECT c::text, ST_AsText(ct_decode(c)) AS decoded, ST_Equals(ct_decode(c), g) AS equal
  FROM (SELECT g, ct_encode(g, 5, 0.4, 1) AS c FROM (SELECT 'POLYGON((0 0,100 0,100 100,0 100,0 0))'::geometry g) s) t;
-- A deep bay whose end is a concave arc: one external circle (negative radius) and its corner points.
SELECT (s->>'internal')::int AS internal, (s->>'external')::int AS external, (s->>'zero')::int AS zero,
       (SELECT round(r::numeric) FROM ct_circles(c) WHERE r < 0) AS external_radius,
       ST_IsValid(ct_decode(c)) AS valid, ct_hausdorff(c, g) <= 5 AS within_max_error
  FROM (SELECT g, ct_encode(g, 5, 0.4, 1) AS c FROM (SELECT ST_Difference('POLYGON((0 0,1000 0,1000 1000,0 1000,0 0))'::geometry,
        ST_Buffer('LINESTRING(500 1100,500 400)'::geometry, 100, 16)) g) s) t,
       LATERAL ct_summary(c) s;
-- Holes and parts survive, with the same SRID.
SELECT ST_NumGeometries(d) AS parts, ST_NumInteriorRings(ST_GeometryN(d, 1)) AS holes, ST_IsValid(d) AS valid, ST_SRID(d) AS srid
  FROM (SELECT ct_decode(ct_encode(ST_SetSRID('MULTIPOLYGON(((0 0,1000 0,1000 1000,0 1000,0 0),(200 200,200 400,400 400,400 200,200 200)),((2000 0,2500 0,2500 500,2000 0)))'::geometry, 2193), 5, 0.4, 10)) d) s;
-- Curved output keeps true arcs: CIRCULARSTRING pieces inside a COMPOUNDCURVE.
SELECT GeometryType(d) AS type, ST_AsText(d) LIKE '%CIRCULARSTRING%' AS has_arcs,
       round(ST_Area(ST_CurveToLine(d, 64))::numeric, -2) AS area, round((pi() * 100 * 100)::numeric, -2) AS disc_area
  FROM (SELECT ct_decode_curved(ct_encode(ST_Buffer(ST_MakePoint(0, 0), 100, 8), 5)) d) s;
SELECT GeometryType(ct_decode_curved(ct_encode('MULTIPOLYGON(((0 0,10 0,10 10,0 0)))'::geometry, 1))) AS type;
-- arc_tolerance strokes arcs finer or coarser
SELECT ST_NPoints(ct_decode(c, 10)) < ST_NPoints(ct_decode(c)) AS coarser, ST_NPoints(ct_decode(c, 0.01)) > ST_NPoints(ct_decode(c)) AS finer
  FROM (SELECT ct_encode(ST_Buffer(ST_MakePoint(0, 0), 100, 8), 5) c) s;
-- Empty in, empty out; NULL in, NULL out.
SELECT ST_AsText(ct_decode(ct_encode('POLYGON EMPTY'::geometry, 5))) AS empty_polygon,
       ST_AsText(ct_decode(ct_encode('MULTIPOLYGON EMPTY'::geometry, 5))) AS empty_multi,
       ct_encode(NULL::geometry, 5) IS NULL AS null_geom, ct_encode('POLYGON EMPTY'::geometry, NULL) IS NULL AS null_radius;
-- Z and M are dropped, with a NOTICE.
SELECT ST_AsText(ct_decode(ct_encode('POLYGON Z((0 0 1,100 0 2,100 100 3,0 100 4,0 0 1))'::geometry, 5, 0.4, 1))) AS dropped_z;
-- Errors: 22023 naming the type or the parameter and its valid range, with a hint.
SELECT ct_encode('POINT(1 2)'::geometry, 5);
SELECT ct_encode('POLYGON((0 0,10 10,10 0,0 10,0 0))'::geometry, 5);
SELECT ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 0);
SELECT sqlstate_of($$SELECT ct_encode('LINESTRING(0 0,1 1)'::geometry, 5)$$);
SELECT sqlstate_of($$SELECT ct_encode('GEOMETRYCOLLECTION(POLYGON((0 0,1 0,1 1,0 0)))'::geometry, 5)$$);
SELECT sqlstate_of($$SELECT ct_encode('CURVEPOLYGON(CIRCULARSTRING(0 0,4 0,4 4,0 4,0 0))'::geometry, 5)$$);
SELECT sqlstate_of($$SELECT ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 'NaN')$$);
SELECT sqlstate_of($$SELECT ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 5, 1.5)$$);
SELECT sqlstate_of($$SELECT ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 5, -0.1)$$);
SELECT sqlstate_of($$SELECT ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 5, 0.4, 0)$$);
SELECT sqlstate_of($$SELECT ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 5, 0.4, NULL, -1)$$);
SELECT sqlstate_of($$SELECT ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 'Infinity')$$);
SELECT sqlstate_of($$SELECT ct_encode(ST_GeomFromText('POLYGON((0 0,10 0,10 NaN,0 0))'), 5)$$);
SELECT sqlstate_of($$SELECT ct_decode(ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 5), 0)$$);
SELECT sqlstate_of($$SELECT ct_decode(ct_encode('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 5), -1)$$);
-- A cancel stops a long encode promptly (interrupts are checked in the long loops). The timeout is
-- past PostGIS's own ST_IsValid of the input (about 0.2 s here), so that it lands in circletree.
CREATE TABLE big AS SELECT ST_Buffer(ST_MakePoint(0, 0), 1000000, 250000) AS g;
SELECT ST_NPoints(g) FROM big;
SET statement_timeout = '1500ms';
SELECT ct_ncircles(ct_encode(g, 0.001, 0.4, 0.001)) FROM big;
RESET statement_timeout;
