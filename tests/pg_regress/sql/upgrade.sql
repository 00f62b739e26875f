-- Upgrade without reload: a database on 0.1.0 with stored (format version 1) values runs
-- ALTER EXTENSION circletree UPDATE; the values keep their bytes and decode to the same geometry
-- (the md5 of the WKB 0.1.0 decoded them to, from tests/data/golden_v1.tsv.gz), and new values
-- are version 2. scripts/test.sh installs 0.1.0's script (tests/upgrade/circletree--0.1.0.sql).
CREATE DATABASE circletree_upgrade;
\c circletree_upgrade
SET client_min_messages = warning;
CREATE EXTENSION postgis;
CREATE EXTENSION circletree VERSION '0.1.0';
RESET client_min_messages;
SELECT extversion FROM pg_extension WHERE extname = 'circletree';
-- lake_tahoe at (50, 0.4, 100), as 0.1.0's ct_encode stored it
CREATE TABLE stored (id int, ct circletree);
INSERT INTO stored VALUES (1, '\x0103c4fd0302010a0108ff0102020202a0018d140901908e09cad434c90f8a1c0130c80884090074cf0200138701003169000e87010090030600c002c10200f40288028803c2038d03a901aa02a407fa0584067a00ea02f6039b03eb09a405cc07da0b9e06ed0491049a0300fa029c04d7048304f00200f504ea05d0069407e60300179002008e11cc068912b711d50400558803000aae02001b7a003d5c0095038902c603eb031a007ba50100f101c601a302f503eb04ea03fd03a00100c7059001af05da038304009505b3028d04d8019d069002d503850100cb05af01b9058004a1040063e9020011930100ec028b01d802a001d3048902fc01a90300188d02000e8d01002e6500aa077df206'::bytea::circletree);
ALTER EXTENSION circletree UPDATE;
SELECT extversion FROM pg_extension WHERE extname = 'circletree';
SELECT ct_summary(ct)->>'format_version' AS version, ct_ncircles(ct) AS circles,
       ct::bytea = '\x0103c4fd0302010a0108ff0102020202a0018d140901908e09cad434c90f8a1c0130c80884090074cf0200138701003169000e87010090030600c002c10200f40288028803c2038d03a901aa02a407fa0584067a00ea02f6039b03eb09a405cc07da0b9e06ed0491049a0300fa029c04d7048304f00200f504ea05d0069407e60300179002008e11cc068912b711d50400558803000aae02001b7a003d5c0095038902c603eb031a007ba50100f101c601a302f503eb04ea03fd03a00100c7059001af05da038304009505b3028d04d8019d069002d503850100cb05af01b9058004a1040063e9020011930100ec028b01d802a001d3048902fc01a90300188d02000e8d01002e6500aa077df206'::bytea AS same_bytes,
       ct::text::circletree::bytea = ct::bytea AS text_round_trip,
       md5(ST_AsBinary(ct_decode(ct))) = 'eec4feffed8c82c0d50ddae6dd183a5c' AS same_geometry_as_0_1_0,
       ST_IsValid(ct_decode(ct)) AS valid
  FROM stored;
INSERT INTO stored SELECT 2, ct_encode(ct_decode(ct), 50, 0.4, 100) FROM stored WHERE id = 1;
SELECT id, ct_summary(ct)->>'format_version' AS version, ST_IsValid(ct_decode(ct)) AS valid,
       ct_hausdorff(ct_decode(s.ct), (SELECT ct_decode(ct) FROM stored WHERE id = 1)) <= 100 AS within
  FROM stored s ORDER BY id;
-- ct_encode_within (0.3.0) and the single-decode ct_decode (0.4.0) after the update
SELECT ct_summary(ct_encode_within(ct_decode(ct), 100))->>'format_version' AS version,
       ct_hausdorff(ct_encode_within(ct_decode(ct), 100), ct_decode(ct)) <= 100 AS within
  FROM stored WHERE id = 1;
-- The updated extension has the objects of a fresh install, with the same function bodies,
-- volatility, strictness, parallel safety and catalog comments (the fresh one is circletree_regress's).
SELECT md5(string_agg(o.descr, E'\n' ORDER BY o.descr)) AS objects
  FROM (SELECT pg_describe_object(d.classid, d.objid, 0) || ' ' ||
               coalesce(p.prosrc || ' ' || p.provolatile::text || p.proisstrict::text || p.proparallel::text, '') || ' ' ||
               coalesce(obj_description(d.objid, d.classid::regclass::name), '') AS descr
          FROM pg_depend d
          LEFT JOIN pg_proc p ON d.classid = 'pg_proc'::regclass AND p.oid = d.objid
         WHERE d.refclassid = 'pg_extension'::regclass AND d.deptype = 'e'
           AND d.refobjid = (SELECT oid FROM pg_extension WHERE extname = 'circletree')) o \gset updated_
\c circletree_regress
SELECT md5(string_agg(o.descr, E'\n' ORDER BY o.descr)) = :'updated_objects' AS same_as_a_fresh_install
  FROM (SELECT pg_describe_object(d.classid, d.objid, 0) || ' ' ||
               coalesce(p.prosrc || ' ' || p.provolatile::text || p.proisstrict::text || p.proparallel::text, '') || ' ' ||
               coalesce(obj_description(d.objid, d.classid::regclass::name), '') AS descr
          FROM pg_depend d
          LEFT JOIN pg_proc p ON d.classid = 'pg_proc'::regclass AND p.oid = d.objid
         WHERE d.refclassid = 'pg_extension'::regclass AND d.deptype = 'e'
           AND d.refobjid = (SELECT oid FROM pg_extension WHERE extname = 'circletree')) o;
DROP DATABASE circletree_upgrade;
