-- A role that is not a superuser, granted only what a reader of a table needs, can use every
-- function (issue 9): nothing needs superuser rights or SECURITY DEFINER, and no function is one.
SELECT count(*) AS security_definer
  FROM pg_proc p JOIN pg_depend d ON d.classid = 'pg_proc'::regclass AND d.objid = p.oid
 WHERE d.refobjid = (SELECT oid FROM pg_extension WHERE extname = 'circletree') AND d.deptype = 'e'
   AND p.prosecdef;
SET client_min_messages = warning;
DROP ROLE IF EXISTS circletree_reader;  -- left by an interrupted run (roles outlive the database)
RESET client_min_messages;
CREATE ROLE circletree_reader NOLOGIN NOSUPERUSER;
GRANT SELECT ON coast TO circletree_reader;
SET ROLE circletree_reader;
SELECT current_user, (SELECT rolsuper FROM pg_roles WHERE rolname = current_user) AS superuser;
SELECT name,
       ST_IsValid(ct_decode(ct_encode(geom, 5, 0.4, 10))) AS encode_decode,
       ct_hausdorff(ct_encode_within(geom, 10), geom) <= 10 AS within,
       ST_GeometryType(ct_decode_curved(ct_encode(geom, 5, 0.4, 10))) AS curved,
       ct_sliver_ratio(ct_encode(geom, 5, 0.4, 10), geom) < 0.01 AS sliver,
       ct_storage_ratio(ct_encode(geom, 5, 0.4, 10), geom) < 1 AS smaller,
       ct_envelope(ct_encode(geom, 5, 0.4, 10)) ~ geom AS envelope,
       (SELECT count(*) FROM ct_circles(ct_encode(geom, 5, 0.4, 10))) = ct_ncircles(ct_encode(geom, 5, 0.4, 10)) AS circles,
       ct_encode(geom, 5, 0.4, 10)::text::circletree = ct_encode(geom, 5, 0.4, 10) AS text_form,
       ct_encode(geom, 5, 0.4, 10)::bytea::circletree = ct_encode(geom, 5, 0.4, 10) AS bytea_form,
       ct_summary(ct_encode(geom, 5, 0.4, 10))->>'format_version' AS version
  FROM coast WHERE name = 'lake_tahoe';
SELECT count(*) AS sweep_rows FROM ct_sweep((SELECT geom FROM coast WHERE name = 'lake_tahoe'), '{5,10}', '{0.4}', '{10}');
-- and its errors are the same clean errors
SELECT sqlstate_of('SELECT ct_encode(''POINT(0 0)''::geometry, 5)');
RESET ROLE;
REVOKE SELECT ON coast FROM circletree_reader;
DROP ROLE circletree_reader;
