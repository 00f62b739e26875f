-- The circletree type's binary I/O, bytea casts and byte-equality operators (the btree and hash
-- operator classes, 0.7.0 on, are in sql/in_place.sql) (loaded by
-- src/datatype/binary.rs with extension_sql_file!, once the functions exist).
ALTER TYPE circletree SET (RECEIVE = circletree_recv, SEND = circletree_send);
-- Stored as EXTERNAL: out of line when large, never pglz-compressed (see docs/FORMAT.md).
ALTER TYPE circletree SET (STORAGE = external);
CREATE CAST (circletree AS bytea) WITH FUNCTION circletree_to_bytea(circletree);
CREATE CAST (bytea AS circletree) WITH FUNCTION circletree_from_bytea(bytea);
CREATE OPERATOR = (LEFTARG = circletree, RIGHTARG = circletree, PROCEDURE = circletree_eq,
    COMMUTATOR = =, NEGATOR = <>, RESTRICT = eqsel, JOIN = eqjoinsel, HASHES, MERGES);
CREATE OPERATOR <> (LEFTARG = circletree, RIGHTARG = circletree, PROCEDURE = circletree_ne,
    COMMUTATOR = <>, NEGATOR = =, RESTRICT = neqsel, JOIN = neqjoinsel);
