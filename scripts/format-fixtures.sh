#!/usr/bin/env bash
# Writes the fixtures of the field readers (tests/formats.rs) into tests/format-fixtures/: the
# register parcels of tests/fields/real/, written by an independent program (GDAL's ogr2ogr,
# Debian's gdal-bin) as zipped Shapefiles in the national grids of their registers and in WGS84.
# The fixtures are kept in the repository; this script is how they were made (GDAL 3.6, PROJ 9.1:
# RD New by EPSG's transformation 4833, the 7-parameter shift "Amersfoort to WGS 84 (4)").
#
#   apt-get install gdal-bin && scripts/format-fixtures.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out=tests/format-fixtures
real=tests/fields/real
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export PROJ_NETWORK=OFF

# shapefile SOURCE NAME CRS [keep-prj]: SOURCE's parcels as NAME.zip in CRS (ogr2ogr writes the
# .prj in ESRI's dialect, as most farm software does: for RD New without its datum shift).
shapefile() {
  local source=$1 name=$2 crs=$3 prj=${4:-keep}
  rm -rf "${tmp:?}/$name"
  mkdir -p "$tmp/$name"
  ogr2ogr -f "ESRI Shapefile" -t_srs "$crs" -lco ENCODING=UTF-8 -nln "$name" \
    "$tmp/$name/$name.shp" "$source"
  [ "$prj" = keep ] || rm "$tmp/$name/$name.prj"
  python3 - "$tmp/$name" "$out/$name.zip" <<'PY'
import os, sys, zipfile
src, dst = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as z:
    for f in sorted(os.listdir(src)):
        info = zipfile.ZipInfo(f, date_time=(2026, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        with open(os.path.join(src, f), "rb") as data:
            z.writestr(info, data.read())
PY
}

# kml SOURCE NAME: SOURCE's parcels as NAME.kml (GDAL's KML driver, each placemark named by
# the parcel's id, the other properties as extended data) and as NAME.kmz (that file zipped as
# doc.kml, as Google Earth does).
kml() {
  local source=$1 name=$2
  rm -f "$out/$name.kml" "$out/$name.kmz"
  ogr2ogr -f KML -dsco NameField=id "$out/$name.kml" "$source"
  python3 - "$out/$name.kml" "$out/$name.kmz" <<'PY'
import sys, zipfile
with zipfile.ZipFile(sys.argv[2], "w", zipfile.ZIP_DEFLATED) as z:
    info = zipfile.ZipInfo("doc.kml", date_time=(2026, 1, 1, 0, 0, 0))
    info.compress_type = zipfile.ZIP_DEFLATED
    z.writestr(info, open(sys.argv[1], "rb").read())
PY
}

shapefile "$real/nl_brp_2023_sample.geojson" nl_brp_rd_new EPSG:28992
shapefile "$real/nl_brp_2023_sample.geojson" nl_brp_wgs84 EPSG:4326
shapefile "$real/nl_brp_2023_sample.geojson" nl_brp_wgs84_no_prj EPSG:4326 drop
shapefile "$real/dk_marker_2026_sample.geojson" dk_marker_etrs89_utm32n EPSG:25832
shapefile "$real/dk_marker_2026_sample.geojson" dk_marker_wgs84_utm32n EPSG:32632
shapefile "$real/dk_marker_2026_sample.geojson" dk_marker_tm35fin EPSG:3067
shapefile "$real/dk_marker_2026_sample.geojson" dk_marker_utm32n_no_prj EPSG:25832 drop
kml "$real/dk_marker_2026_sample.geojson" dk_marker
ls -l "$out"
