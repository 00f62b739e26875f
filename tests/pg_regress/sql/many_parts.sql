-- A MultiPolygon of many small, alike parts (a grid of 10,000 parcels, 1 m squares 2 m apart):
-- version 2 codes a part in under the 5 bytes version 1 needs, so its reader bounds the part count
-- by version 2's own stream budget. Stored, read, decoded and compared: nothing is lost.
CREATE TEMP TABLE parcels AS
SELECT ST_SetSRID(ST_Collect(ST_MakeEnvelope(x * 2, y * 2, x * 2 + 1, y * 2 + 1) ORDER BY x, y), 2193) AS geom
  FROM generate_series(0, 99) x, generate_series(0, 99) y;
CREATE TEMP TABLE stored AS SELECT ct_encode_within(geom, 0.1) AS ct, ct_encode(geom, 0.05, 0.4, 0.1) AS paper FROM parcels;
SELECT ct_ncircles(ct) AS circles, pg_column_size(ct) < 5 * 10000 AS under_5_bytes_a_part,
       ST_NumGeometries(ct_decode(ct)) AS parts, ST_IsValid(ct_decode(ct)) AS valid,
       ct_hausdorff(ct, geom) <= 0.1 AS within, ct_srid(ct) AS srid
  FROM stored, parcels;
SELECT ST_NumGeometries(ct_decode(paper)) AS parts, ST_IsValid(ct_decode(paper)) AS valid,
       ct_hausdorff(paper, geom) <= 0.1 AS within
  FROM stored, parcels;
-- every way in and out keeps the bytes
SELECT ct::text::circletree = ct AS text, ct::bytea::circletree = ct AS bytea,
       ST_Covers(ct_envelope(ct), geom) AND ST_Covers(ct_envelope(ct), ct_decode(ct)) AS envelope_covers
  FROM stored, parcels;
