-- ct_svg (issue 10 item 1): an SVG for every sample polygon, well-formed XML, one <circle> a stored
-- circle (points included), the original drawn when given, and the width checked.
SELECT count(*) AS polygons,
       count(*) FILTER (WHERE xml_is_well_formed_document(s)) AS well_formed,
       count(*) FILTER (WHERE (length(s) - length(replace(s, '<circle', ''))) / 7 = ct_ncircles(ct)) AS a_circle_each,
       count(*) FILTER (WHERE s LIKE '%id="original"%') AS with_original
  FROM (SELECT ct, ct_svg(ct, geom, 400) AS s FROM (SELECT geom, ct_encode_within(geom, 250) AS ct FROM coast) e) d;
-- the paper's circles: inside and outside circles in the legend, as counted by ct_summary
SELECT ct_svg(ct) LIKE '%' || (ct_summary(ct)->>'internal') || ' circles inside (r &gt; 0)%' AS inside_counted,
       ct_svg(ct) LIKE '%' || (ct_summary(ct)->>'external') || ' circles outside (r &lt; 0)%' AS outside_counted,
       ct_svg(ct) NOT LIKE '%original boundary%' AS no_original_without_geom,
       ct_svg(ct) LIKE '<svg%width="800"%' AS default_width
  FROM (SELECT ct_encode(geom, 5, 0.4, 10) AS ct FROM coast WHERE name = 'kapiti_island_linz') e;
SELECT ct_svg(NULL::circletree) IS NULL AS null_in_null_out;
SELECT sqlstate_of($$SELECT ct_svg(ct_encode_within('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 1), NULL, 0)$$);
SELECT sqlstate_of($$SELECT ct_svg(ct_encode_within('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 1), NULL, 100000)$$);
SELECT sqlstate_of($$SELECT ct_svg(ct_encode_within('POLYGON((0 0,10 0,10 10,0 0))'::geometry, 1), 'POINT(0 0)'::geometry)$$);
