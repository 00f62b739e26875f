-- Longitude/latitude data (issue 10 item 8). On EPSG:4326 lengths are degrees: a length of a
-- degree or more is refused as metres given by mistake (22023, naming the geography path), smaller
-- ones are degrees as in PostGIS. The geography overloads take metres: they encode in the UTM zone
-- of the data (ct_utm_srid), the value keeps that SRID, and ct_decode_geography brings it back.
CREATE TEMP TABLE ll AS
  SELECT name, geom AS utm, ST_Transform(geom, 4326) AS geom FROM coast
   WHERE name IN ('rarotonga', 'lake_tahoe', 'kapiti_island_linz');
SELECT name, ST_SRID(utm) AS stored_srid, ct_utm_srid(geom::geography) AS utm_zone_srid FROM ll ORDER BY name;
-- metres on degrees: refused, with the way out in the message
SELECT sqlstate_of($$SELECT ct_encode(geom, 5, 0.4, 10) FROM ll WHERE name = 'rarotonga'$$);
SELECT sqlstate_of($$SELECT ct_encode_within(geom, 10) FROM ll WHERE name = 'rarotonga'$$);
-- degrees on degrees: accepted (1e-4 degrees is about 10 m)
SELECT name, ct_srid(c) AS srid, ST_IsValid(ct_decode(c)) AS valid, ct_hausdorff(c, geom) <= 1e-4 AS within
  FROM ll, LATERAL (SELECT ct_encode_within(geom, 1e-4) AS c) e ORDER BY name;
-- metres on geography: the value is in the UTM zone, valid and within the bound in that zone's
-- metres (checked against the original in the same zone), and decodes back to 4326
SELECT name, ct_srid(c) AS srid, ST_IsValid(ct_decode(c)) AS valid,
       ct_hausdorff(c, ST_Transform(geom, ct_srid(c))) <= 10 AS within_10_m,
       ST_SRID(ct_decode_geography(c)::geometry) AS back_srid,
       ST_Area(ct_decode_geography(c)) / ST_Area(geom::geography) BETWEEN 0.99 AND 1.01 AS same_area
  FROM ll, LATERAL (SELECT ct_encode_within(geom::geography, 10) AS c) e ORDER BY name;
SELECT name, ct_srid(c) AS srid, ST_IsValid(ct_decode(c)) AS valid,
       ct_hausdorff(c, ST_Transform(geom, ct_srid(c))) <= 10 AS within_10_m
  FROM ll, LATERAL (SELECT ct_encode(geom::geography, 5, 0.4, 10) AS c) e ORDER BY name;
-- the same bytes as encoding the stored UTM geometry's reprojection by hand
SELECT name, ct_encode_within(geom::geography, 10) = ct_encode_within(ST_Transform(geom, ct_utm_srid(geom::geography)), 10) AS same
  FROM ll ORDER BY name;
-- zones: north, south, both sides of the antimeridian's neighbours, and the poles (UPS)
SELECT ct_utm_srid(ST_MakeEnvelope(x, y, x + 0.1, y + 0.1, 4326)::geography) AS srid, x, y
  FROM (VALUES (-180, 10), (179.8, -10), (0, 0), (3, 60), (-120, 39), (10, 85), (10, -85)) AS t(x, y);
-- an untyped literal still means a geometry (text overloads keep it unambiguous)
SELECT ct_ncircles(ct_encode('POLYGON((0 0,100 0,100 100,0 100,0 0))', 5)) > 0 AS literal_encodes,
       ct_ncircles(ct_encode_within('POLYGON((0 0,100 0,100 100,0 100,0 0))', 5)) > 0 AS literal_within;
-- SRID 0 and projected SRIDs are never taken for degrees
SELECT ct_ncircles(ct_encode(ST_SetSRID(geom, 0), 5, 0.4, 10)) > 0 AS srid_0,
       ct_ncircles(ct_encode(utm, 5, 0.4, 10)) > 0 AS utm
  FROM ll WHERE name = 'rarotonga';
