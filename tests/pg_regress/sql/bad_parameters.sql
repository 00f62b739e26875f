-- Bad input, parameter class: every numeric parameter of every function, out of range or not
-- finite, and NULLs. Each ends in 22023 (or 22004 for a NULL where one is not allowed) with a hint;
-- a STRICT function gives NULL for a NULL argument.
CREATE TEMP TABLE p AS SELECT ct_encode(geom, 5, 0.4, 10) AS ct, geom FROM coast WHERE name = 'rarotonga';
CREATE TEMP TABLE bad(v text);
INSERT INTO bad VALUES ('0'), ('-1'), ('''NaN'''), ('''Infinity'''), ('''-Infinity'''), ('1e-300'), ('1e300');
SELECT v,
       outcome(format('SELECT ct_encode(geom, %s, 0.4, 10) FROM p', v)) AS min_radius,
       outcome(format('SELECT ct_encode(geom, 5, %s, 10) FROM p', v)) AS overlap,
       outcome(format('SELECT ct_encode(geom, 5, 0.4, %s) FROM p', v)) AS dp_tolerance
FROM bad ORDER BY v;
SELECT v,
       outcome(format('SELECT ct_encode(geom, 5, 0.4, 10, %s) FROM p', v)) AS max_error,
       outcome(format('SELECT ct_encode_within(geom, %s) FROM p', v)) AS within_max_error,
       outcome(format('SELECT ct_decode(ct, %s) FROM p', v)) AS arc_tolerance
FROM bad ORDER BY v;
-- overlap outside [0, 1] just past its ends
SELECT outcome('SELECT ct_encode(geom, 5, 1.0000001, 10) FROM p') AS over_one,
       outcome('SELECT ct_encode(geom, 5, -0.0000001, 10) FROM p') AS below_zero,
       outcome('SELECT ct_encode(geom, 5, 1, 10) FROM p') AS one,
       outcome('SELECT ct_encode(geom, 5, 0, 10) FROM p') AS zero;
-- ct_sweep's arrays: empty, NULL elements, bad values, multidimensional, too many combinations
SELECT a, outcome(format('SELECT count(*) FROM p, ct_sweep(geom, %s, ARRAY[0.4], ARRAY[10])', a)) AS min_radii,
          outcome(format('SELECT count(*) FROM p, ct_sweep(geom, ARRAY[5], %s, ARRAY[10])', a)) AS overlaps,
          outcome(format('SELECT count(*) FROM p, ct_sweep(geom, ARRAY[5], ARRAY[0.4], %s)', a)) AS dp_tolerances
FROM (VALUES ('ARRAY[]::float8[]'), ('ARRAY[NULL]::float8[]'), ('ARRAY[5, NULL]::float8[]'),
             ('ARRAY[''NaN'']::float8[]'), ('ARRAY[-1]::float8[]'), ('ARRAY[[5], [6]]::float8[]')) AS t(a)
ORDER BY a;
-- a million combinations is a million encodes, as the user asked: statement_timeout stops it.
-- Each row of the sweep also runs PostGIS's ST_IsValid; when the timeout lands inside GEOS, PostGIS
-- reports it as XX000 'GEOS isvalid() threw an error!' rather than 57014: that outcome is
-- expected/bad_parameters_1.out (pg_regress's alternative file), identical but for that line.
\set VERBOSITY terse
SET statement_timeout = '1s';
SELECT count(*) FROM p, ct_sweep(geom, array_fill(5::float8, ARRAY[1000]), array_fill(0.4::float8, ARRAY[1000]), ARRAY[10]);
RESET statement_timeout;
\set VERBOSITY default
SELECT count(*) AS backend_usable_after FROM p, ct_sweep(geom, ARRAY[5], ARRAY[0.4], ARRAY[10]);
-- NULL arguments: NULL out for the STRICT functions, never a crash
SELECT ct_encode(NULL::geometry, 5) IS NULL AS encode_null_geom,
       ct_encode(geom, NULL) IS NULL AS encode_null_radius,
       ct_encode_within(geom, NULL) IS NULL AS within_null,
       ct_decode(ct, NULL) IS NULL AS decode_null_tolerance,
       ct_sliver_error(ct, NULL) IS NULL AS sliver_null,
       ct_hausdorff(NULL::circletree, geom) IS NULL AS hausdorff_null
FROM p;
SELECT outcome('SELECT ct_encode(geom, 5, NULL, 10) FROM p') AS null_overlap,
       outcome('SELECT ct_encode(geom, 5, 0.4, NULL) FROM p') AS null_dp;
-- no parameter error is internal or comes without a hint
SELECT count(*) AS outcomes,
       count(*) FILTER (WHERE o LIKE 'XX%' OR o LIKE '% NO HINT:%') AS internal_or_unhinted,
       count(*) FILTER (WHERE o = 'ok') AS accepted
FROM bad, LATERAL (VALUES
  (outcome(format('SELECT ct_encode(geom, %s, 0.4, 10) FROM p', v))),
  (outcome(format('SELECT ct_encode(geom, 5, %s, 10) FROM p', v))),
  (outcome(format('SELECT ct_encode(geom, 5, 0.4, %s) FROM p', v))),
  (outcome(format('SELECT ct_encode(geom, 5, 0.4, 10, %s) FROM p', v))),
  (outcome(format('SELECT ct_encode_within(geom, %s) FROM p', v))),
  (outcome(format('SELECT ct_decode(ct, %s) FROM p', v))),
  (outcome(format('SELECT count(*) FROM p, ct_sweep(geom, ARRAY[%s]::float8[], ARRAY[0.4], ARRAY[10])', v)))) AS t(o);
