-- Upgrade without reload: a database on 0.1.0 with stored (format version 1) values runs
-- ALTER EXTENSION circletree UPDATE; the values keep their bytes and decode to the same geometry
-- (the md5 of the WKB 0.1.0 decoded them to, from tests/data/golden_v1.tsv.gz), and new values
-- are version 2. scripts/test.sh installs every earlier release's script (tests/upgrade/).
CREATE DATABASE circletree_upgrade;
\c circletree_upgrade
SET client_min_messages = warning;
CREATE EXTENSION postgis;
-- The objects of a fresh install, with their function bodies, volatility, strictness, parallel safety
-- and catalog comments, as one md5.
CREATE EXTENSION circletree;
CREATE FUNCTION pg_temp.ct_objects() RETURNS text LANGUAGE sql AS $$
SELECT md5(string_agg(o.descr, E'\n' ORDER BY o.descr))
  FROM (SELECT pg_describe_object(d.classid, d.objid, 0) || ' ' ||
               coalesce(p.prosrc || ' ' || p.provolatile::text || p.proisstrict::text || p.proparallel::text, '') || ' ' ||
               coalesce(obj_description(d.objid, d.classid::regclass::name), '') AS descr
          FROM pg_depend d
          LEFT JOIN pg_proc p ON d.classid = 'pg_proc'::regclass AND p.oid = d.objid
         WHERE d.refclassid = 'pg_extension'::regclass AND d.deptype = 'e'
           AND d.refobjid = (SELECT oid FROM pg_extension WHERE extname = 'circletree')) o
$$;
SELECT pg_temp.ct_objects() AS objects \gset fresh_
DROP EXTENSION circletree;
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
-- The updated extension has the objects of a fresh install.
SELECT pg_temp.ct_objects() = :'fresh_objects' AS same_as_a_fresh_install;
-- Every later release, from its own frozen install script (tests/upgrade/, installed by scripts/test.sh):
-- a format-1 value (0.1.0's, above) and a format-2 one (kapiti_island_linz at ct_encode_within 25, as
-- 0.2.0 and 0.3.0 stored it: tests/data/golden_v2.tsv.gz) stored under it keep their bytes and their
-- geometry through the update, and the updated objects are a fresh install's.
CREATE TEMP TABLE kept (id int, bytes bytea, wkb_md5 text);
INSERT INTO kept SELECT 1, ct::bytea, md5(ST_AsBinary(ct_decode(ct))) FROM stored WHERE id = 1;
INSERT INTO kept VALUES (2, '\x0203f0ff0346003200000001ec26fe3200ed0fddfd010001848f01c48a13cc01e2013bf9889c2c4b540d473479c6e6a2f125412494d6427e46ff1eb6accd8e7d75e6080c5d81a1e52947ef05d8376c3921b0454ad70a68449f73c279e0c89271068d3337e16a94416db0c278f45a9240f779c1fc0db646927ca73327d6fd0b64c6d5d157e5b018de2fd02407c18129942cff818c9a5aabb93fccbfedf8daff26c6455aa675ef829ee49e8c', '31a0ee984a0ac27b8bf6a6bf4cf02cc2');
DROP TABLE stored;
DROP EXTENSION circletree;
CREATE FUNCTION pg_temp.from_release(version text, fresh text) RETURNS TABLE (from_version text, to_version text,
    values_kept bool, same_as_a_fresh_install bool) LANGUAGE plpgsql AS $$
BEGIN
  EXECUTE format('CREATE EXTENSION circletree VERSION %L', version);
  CREATE TEMP TABLE stored_under AS SELECT k.id, k.bytes::circletree AS ct FROM pg_temp.kept k;
  ALTER EXTENSION circletree UPDATE;
  RETURN QUERY
    SELECT version, (SELECT extversion::text FROM pg_extension WHERE extname = 'circletree'),
           (SELECT bool_and(s.ct::bytea = k.bytes AND md5(ST_AsBinary(ct_decode(s.ct))) = k.wkb_md5)
                   AND count(*) = 2
              FROM stored_under s JOIN pg_temp.kept k USING (id)),
           pg_temp.ct_objects() = fresh;
  DROP TABLE stored_under;
  DROP EXTENSION circletree;
END $$;
SET client_min_messages = warning;
SELECT r.* FROM unnest(ARRAY['0.1.0', '0.2.0', '0.3.0', '0.4.0', '0.5.0', '0.6.0']) v,
       pg_temp.from_release(v, :'fresh_objects') r;
RESET client_min_messages;
\c circletree_regress
DROP DATABASE circletree_upgrade;
