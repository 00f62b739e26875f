-- circletree 0.1.0 -> 0.2.0 (ALTER EXTENSION circletree UPDATE).
-- 0.2.0 changes no SQL object: the same functions, in the new library, read format versions 1 and 2
-- and ct_encode writes version 2. Values stored by 0.1.0 stay version 1, unchanged and readable; they
-- become version 2 only when encoded again (UPDATE t SET ct = ct_encode(geom, ...)).
-- cargo pgrx install copies this file (sql/<ext>--<from>--<to>.sql) beside the generated script.
SELECT 1 WHERE false;
