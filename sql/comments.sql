-- Catalog documentation: what \dT+ circletree and \df+ ct_* show. Loaded last by src/lib.rs
-- (extension_sql_file!), and repeated in the upgrade script of each release that changed it
-- (sql/circletree--0.3.0--0.4.0.sql introduced it; sql/circletree--0.6.0--0.7.0.sql holds this text).
COMMENT ON TYPE @extschema@.circletree IS
  'A polygon stored as ordered circles (x, y, ±r), rebuilt from tangents and arcs; valid and within its recorded max_error (Hausdorff) of the original. See docs/FORMAT.md.';
COMMENT ON FUNCTION @extschema@.ct_encode(geometry, float8, float8, float8, float8) IS
  'ct_encode(geom, min_radius, overlap DEFAULT 0.4, dp_tolerance DEFAULT NULL, max_error DEFAULT NULL): the paper''s circles (medial circles of at least min_radius, overlapping by at most overlap, Douglas-Peucker points at dp_tolerance), repaired until ct_decode is valid and within max_error (NULL: greatest(min_radius, dp_tolerance)). Lengths in the SRID''s units.';
COMMENT ON FUNCTION @extschema@.ct_encode_within(geometry, float8) IS
  'ct_encode_within(geom, max_error): the fewest bytes whose ct_decode is valid and within max_error (continuous Hausdorff, in the SRID''s units).';
COMMENT ON FUNCTION @extschema@.ct_encode(geography, float8, float8, float8, float8) IS
  'ct_encode(geog, min_radius, ...): ct_encode in metres for longitude/latitude data: the geography projected to the WGS 84 UTM zone of its centre (ct_utm_srid), whose SRID the value keeps; ct_decode_geography brings it back.';
COMMENT ON FUNCTION @extschema@.ct_encode_within(geography, float8) IS
  'ct_encode_within(geog, max_error): ct_encode_within in metres for longitude/latitude data, in the UTM zone of its centre (ct_utm_srid).';
COMMENT ON FUNCTION @extschema@.ct_encode(text, float8, float8, float8, float8) IS
  'ct_encode(text, ...): the text read as a geometry (so an untyped literal is not ambiguous between geometry and geography).';
COMMENT ON FUNCTION @extschema@.ct_encode_within(text, float8) IS
  'ct_encode_within(text, max_error): the text read as a geometry.';
COMMENT ON FUNCTION @extschema@.ct_utm_srid(geography) IS
  'ct_utm_srid(geog): the SRID of the WGS 84 UTM zone of the centre of geog''s bounding box (32601-32660 north, 32701-32760 south; UPS 32661 north of 84N, 32761 south of 80S), where the geography overloads encode.';
COMMENT ON FUNCTION @extschema@.ct_decode_geography(@extschema@.circletree, int) IS
  'ct_decode_geography(ct, srid DEFAULT 4326): ct_decode(ct) transformed to the longitude/latitude SRID srid, as geography.';
COMMENT ON FUNCTION @extschema@.ct_svg(@extschema@.circletree, geometry, int) IS
  'ct_svg(ct, geom DEFAULT NULL, width DEFAULT 800): an SVG picture: circles inside (blue) and outside (red), boundary points (green), the rebuilt polygon (black) and, when given, the original (grey), with a legend.';
COMMENT ON FUNCTION @extschema@._ct_svg_wkb(@extschema@.circletree, bytea, int) IS
  'Internal: ct_svg with the original as WKB.';
COMMENT ON FUNCTION @extschema@._ct_srid_is_lonlat(int) IS
  'Internal: whether spatial_ref_sys gives the SRID longitude/latitude units (degrees).';
COMMENT ON FUNCTION @extschema@._ct_check_degrees(bool, int, float8, float8, float8) IS
  'Internal: true, or an ERROR when a longitude/latitude SRID meets a length of a degree or more (metres given by mistake).';
COMMENT ON FUNCTION @extschema@._ct_invalid_reason(geometry) IS
  'Internal: ST_IsValidReason of an invalid Polygon or MultiPolygon, else NULL.';
COMMENT ON FUNCTION @extschema@.ct_decode(@extschema@.circletree) IS
  'ct_decode(ct): the rebuilt POLYGON or MULTIPOLYGON, SRID kept, arcs stroked to the value''s grid step.';
COMMENT ON FUNCTION @extschema@.ct_decode(@extschema@.circletree, float8) IS
  'ct_decode(ct, arc_tolerance): the rebuilt polygon with arcs stroked so no chord lies farther than arc_tolerance from its arc (NULL: the grid step; validity is guaranteed up to the grid step).';
COMMENT ON FUNCTION @extschema@.ct_decode_curved(@extschema@.circletree) IS
  'ct_decode_curved(ct): the rebuilt CURVEPOLYGON or MULTISURFACE with true circular arcs, SRID kept.';
COMMENT ON FUNCTION @extschema@.ct_envelope(@extschema@.circletree) IS
  'ct_envelope(ct): a box holding both the original and ct_decode(ct) (the stored bounding box widened by max_error), read from the header without decoding a circle (the key of the native index, CREATE INDEX ... USING gist (ct)).';
COMMENT ON FUNCTION @extschema@._ct_envelope_ewkb(@extschema@.circletree) IS
  'Internal: ct_envelope as EWKB, from the header alone.';
COMMENT ON FUNCTION @extschema@.ct_circles(@extschema@.circletree) IS
  'ct_circles(ct): the stored circles in boundary order: part, ring, seq (1-based), centre x, y and signed radius r (> 0 inside, < 0 outside, 0 a boundary point).';
COMMENT ON FUNCTION @extschema@.ct_ncircles(@extschema@.circletree) IS
  'ct_ncircles(ct): number of stored circles in all rings (a repeated circle counts each time).';
COMMENT ON FUNCTION @extschema@.ct_srid(@extschema@.circletree) IS
  'ct_srid(ct): the SRID the value was encoded with (read from its header).';
COMMENT ON FUNCTION @extschema@.ct_memsize(@extschema@.circletree) IS
  'ct_memsize(ct): bytes of the value in memory, varlena header included (as ST_MemSize).';
COMMENT ON FUNCTION @extschema@.ct_summary(@extschema@.circletree) IS
  'ct_summary(ct): everything about a value as jsonb: format version, SRID, kind, parts, rings, circles by kind, grid, bytes, original vertices and WKB bytes, parameters.';
COMMENT ON FUNCTION @extschema@.ct_storage_ratio(@extschema@.circletree) IS
  'ct_storage_ratio(ct): ct_memsize over the WKB bytes of the original (recorded at encode time).';
COMMENT ON FUNCTION @extschema@.ct_storage_ratio(@extschema@.circletree, geometry) IS
  'ct_storage_ratio(ct, geom): pg_column_size(ct) over pg_column_size(geom).';
COMMENT ON FUNCTION @extschema@.ct_sliver_error(@extschema@.circletree, geometry) IS
  'ct_sliver_error(ct, geom): area of the symmetric difference between ct_decode(ct) and geom (the SRID''s units squared); an invalid geom is refused (22023).';
COMMENT ON FUNCTION @extschema@.ct_sliver_ratio(@extschema@.circletree, geometry) IS
  'ct_sliver_ratio(ct, geom): ct_sliver_error over ST_Area(geom).';
COMMENT ON FUNCTION @extschema@.ct_hausdorff(@extschema@.circletree, geometry) IS
  'ct_hausdorff(ct, geom): continuous Hausdorff distance between the boundaries of the rebuilt polygon (true arcs) and geom: whole segments, not only vertices.';
COMMENT ON FUNCTION @extschema@.ct_hausdorff(geometry, geometry) IS
  'ct_hausdorff(a, b): the same continuous Hausdorff distance between the boundaries of any two (Multi)Polygons, e.g. to measure ST_Simplify''s result the way circletree is measured.';
COMMENT ON FUNCTION @extschema@.ct_sweep(geometry, float8[], float8[], float8[]) IS
  'ct_sweep(geom, min_radius[], overlap[], dp_tolerance[]): the paper''s experiment: one ct_encode per combination, with circles by kind, bytes, storage ratio, sliver ratio, Hausdorff distance and validity.';
COMMENT ON FUNCTION @extschema@._ct_encode_wkb(bytea, int, text, float8, float8, float8, float8) IS
  'Internal: ct_encode on WKB with PostGIS''s verdict passed in (called by ct_encode up to release 0.5.0).';
COMMENT ON FUNCTION @extschema@._ct_encode_within_wkb(bytea, int, text, float8) IS
  'Internal: ct_encode_within on WKB with PostGIS''s verdict passed in (called by ct_encode_within up to release 0.5.0).';
COMMENT ON FUNCTION @extschema@._ct_encode_geom(geometry, bytea, int, regprocedure, regprocedure, float8, float8, float8, float8) IS
  'Internal: ct_encode of the geometry (its WKB and SRID), asking PostGIS''s ST_IsValid and ST_IsValidReason (the two functions given) beside the encoder (called by ct_encode).';
COMMENT ON FUNCTION @extschema@._ct_encode_within_geom(geometry, bytea, int, regprocedure, regprocedure, float8) IS
  'Internal: ct_encode_within of the geometry (its WKB and SRID), asking PostGIS''s ST_IsValid and ST_IsValidReason (the two functions given) beside the encoder (called by ct_encode_within).';
COMMENT ON FUNCTION @extschema@._ct_decode_ewkb(@extschema@.circletree, float8) IS
  'Internal: the rebuilt polygon as EWKB (called by ct_decode).';
COMMENT ON FUNCTION @extschema@._ct_decode_curved_ewkt(@extschema@.circletree) IS
  'Internal: the rebuilt polygon with true arcs as EWKT (called by ct_decode_curved).';
COMMENT ON FUNCTION @extschema@._ct_decode_wkb(@extschema@.circletree, float8) IS
  'Internal, kept for databases not yet updated from 0.3.0: the rebuilt polygon as WKB.';
COMMENT ON FUNCTION @extschema@._ct_decode_curved_wkt(@extschema@.circletree) IS
  'Internal, kept for databases not yet updated from 0.3.0: the rebuilt polygon with true arcs as WKT.';
COMMENT ON FUNCTION @extschema@._ct_sliver_error_wkb(@extschema@.circletree, bytea) IS
  'Internal: ct_sliver_error against WKB (0.4.0''s wrappers; 0.5.0''s pass the validity too).';
COMMENT ON FUNCTION @extschema@._ct_sliver_error_wkb(@extschema@.circletree, bytea, text) IS
  'Internal: ct_sliver_error against WKB, refusing an invalid original (its ST_IsValidReason).';
COMMENT ON FUNCTION @extschema@._ct_hausdorff_wkb(@extschema@.circletree, bytea) IS
  'Internal: ct_hausdorff against WKB.';
COMMENT ON FUNCTION @extschema@._ct_hausdorff_wkb2(bytea, bytea) IS
  'Internal: ct_hausdorff between two WKB polygons.';
COMMENT ON FUNCTION @extschema@.circletree_in(cstring) IS
  'Text input: SRID=n;CIRCLETREE(...) as circletree::text prints it (docs/FORMAT.md).';
COMMENT ON FUNCTION @extschema@.circletree_out(@extschema@.circletree) IS
  'Text output: every header field and circle, exact (reads back to the same bytes).';
COMMENT ON FUNCTION @extschema@.circletree_recv(internal) IS
  'Binary input (COPY BINARY, binary protocol): the stored bytes, fully checked.';
COMMENT ON FUNCTION @extschema@.circletree_send(@extschema@.circletree) IS
  'Binary output: the stored bytes.';
COMMENT ON FUNCTION @extschema@.circletree_eq(@extschema@.circletree, @extschema@.circletree) IS
  'Byte equality of two values.';
COMMENT ON FUNCTION @extschema@.circletree_ne(@extschema@.circletree, @extschema@.circletree) IS
  'Byte inequality of two values.';
COMMENT ON FUNCTION @extschema@.circletree_to_bytea(@extschema@.circletree) IS
  'The stored bytes as bytea (circletree::bytea).';
COMMENT ON FUNCTION @extschema@.circletree_from_bytea(bytea) IS
  'bytea::circletree: stored bytes of any format version, fully checked (22P03 when corrupt).';
COMMENT ON OPERATOR @extschema@.= (@extschema@.circletree, @extschema@.circletree) IS
  'Byte equality of two values.';
COMMENT ON OPERATOR @extschema@.<> (@extschema@.circletree, @extschema@.circletree) IS
  'Byte inequality of two values.';
COMMENT ON FUNCTION @extschema@.circletree_cmp(@extschema@.circletree, @extschema@.circletree) IS
  'Byte order of two values (-1, 0, 1): the btree operator class, for ORDER BY, DISTINCT, GROUP BY and merge joins; no spatial meaning.';
COMMENT ON FUNCTION @extschema@.circletree_lt(@extschema@.circletree, @extschema@.circletree) IS
  'Byte order: a < b.';
COMMENT ON FUNCTION @extschema@.circletree_le(@extschema@.circletree, @extschema@.circletree) IS
  'Byte order: a <= b.';
COMMENT ON FUNCTION @extschema@.circletree_gt(@extschema@.circletree, @extschema@.circletree) IS
  'Byte order: a > b.';
COMMENT ON FUNCTION @extschema@.circletree_ge(@extschema@.circletree, @extschema@.circletree) IS
  'Byte order: a >= b.';
COMMENT ON FUNCTION @extschema@.circletree_hash(@extschema@.circletree) IS
  'Hash of the stored bytes (PostgreSQL''s hashvarlena, as bytea''s): the hash operator class, for hash joins and hashed GROUP BY.';
COMMENT ON OPERATOR @extschema@.< (@extschema@.circletree, @extschema@.circletree) IS 'Byte order.';
COMMENT ON OPERATOR @extschema@.<= (@extschema@.circletree, @extschema@.circletree) IS 'Byte order.';
COMMENT ON OPERATOR @extschema@.> (@extschema@.circletree, @extschema@.circletree) IS 'Byte order.';
COMMENT ON OPERATOR @extschema@.>= (@extschema@.circletree, @extschema@.circletree) IS 'Byte order.';
COMMENT ON FUNCTION @extschema@._ct_to_geography(@extschema@.circletree) IS
  'Internal: the circletree::geography cast (ct_decode_geography(ct), in EPSG:4326).';
COMMENT ON FUNCTION @extschema@._ct_overlaps(@extschema@.circletree, geometry) IS
  'Internal: ct && geom, the envelope meets the geometry''s box.';
COMMENT ON FUNCTION @extschema@._ct_overlaps_g(geometry, @extschema@.circletree) IS
  'Internal: geom && ct.';
COMMENT ON FUNCTION @extschema@._ct_overlaps_ct(@extschema@.circletree, @extschema@.circletree) IS
  'Internal: a && b, the two envelopes meet.';
COMMENT ON OPERATOR @extschema@.&& (@extschema@.circletree, geometry) IS
  'The envelope (ct_envelope) meets the geometry''s box; indexed by CREATE INDEX ... USING gist (ct).';
COMMENT ON OPERATOR @extschema@.&& (geometry, @extschema@.circletree) IS
  'The geometry''s box meets the envelope (ct_envelope).';
COMMENT ON OPERATOR @extschema@.&& (@extschema@.circletree, @extschema@.circletree) IS
  'The two envelopes (ct_envelope) meet.';
COMMENT ON FUNCTION @extschema@._ct_gist_compress(internal) IS
  'Internal: GiST compress, a circletree to its envelope as a box.';
COMMENT ON FUNCTION @extschema@._ct_gist_consistent(internal, @extschema@.circletree, int2, oid, internal) IS
  'Internal: GiST consistent for &&.';
COMMENT ON FUNCTION @extschema@._ct_support(internal) IS
  'Internal: planner support of ct_intersects, ct_contains and ct_dwithin (an index condition on a circletree GiST index).';
COMMENT ON FUNCTION @extschema@.ct_intersects(@extschema@.circletree, geometry) IS
  'ct_intersects(ct, geom): ST_Intersects(ct_decode(ct), geom), answered from a cached, edge-indexed rebuild; uses a GiST index on ct with no && written.';
COMMENT ON FUNCTION @extschema@.ct_intersects(geometry, @extschema@.circletree) IS
  'ct_intersects(geom, ct): ST_Intersects(geom, ct_decode(ct)).';
COMMENT ON FUNCTION @extschema@.ct_contains(@extschema@.circletree, geometry) IS
  'ct_contains(ct, geom): ST_Contains(ct_decode(ct), geom), from a cached, edge-indexed rebuild; uses a GiST index on ct.';
COMMENT ON FUNCTION @extschema@.ct_contains(geometry, @extschema@.circletree) IS
  'ct_contains(geom, ct): ST_Contains(geom, ct_decode(ct)).';
COMMENT ON FUNCTION @extschema@.ct_dwithin(@extschema@.circletree, geometry, float8) IS
  'ct_dwithin(ct, geom, distance): ST_DWithin(ct_decode(ct), geom, distance), from a cached, edge-indexed rebuild; uses a GiST index on ct.';
COMMENT ON FUNCTION @extschema@.ct_dwithin(geometry, @extschema@.circletree, float8) IS
  'ct_dwithin(geom, ct, distance): ST_DWithin(geom, ct_decode(ct), distance).';
COMMENT ON FUNCTION @extschema@.ct_distance(@extschema@.circletree, geometry) IS
  'ct_distance(ct, geom): ST_Distance(ct_decode(ct), geom), from a cached, edge-indexed rebuild.';
COMMENT ON FUNCTION @extschema@.ct_distance(geometry, @extschema@.circletree) IS
  'ct_distance(geom, ct): ST_Distance(geom, ct_decode(ct)).';
