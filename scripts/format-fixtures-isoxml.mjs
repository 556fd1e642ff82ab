// Writes the ISOXML fixtures of the field readers (tests/formats.rs) with an independent program,
// the npm isoxml package (dev4Agriculture): the register parcels of tests/fields/real/ as TaskData
// partfields, each with its boundary (PLN type 1, holes as interior line strings) and an AB line
// (a guidance group's pattern in version 4; a line string of type 5 in version 3) along its
// first edge. Kept in tests/format-fixtures/; this script is how they were made.
//
//   node scripts/format-fixtures-isoxml.mjs
import { readFileSync, writeFileSync } from "node:fs";
import { ISOXMLManager } from "isoxml";

const out = new URL("../tests/format-fixtures/", import.meta.url);
const real = new URL("../tests/fields/real/", import.meta.url);

async function taskdata(source, version) {
  const parcels = JSON.parse(readFileSync(new URL(source, real), "utf8")).features;
  const m = new ISOXMLManager({ version, fmisTitle: "format fixtures", fmisVersion: "1" });
  const point = (type, [lon, lat]) => m.createEntityFromAttributes("PNT", { PointType: type, PointNorth: lat, PointEast: lon });
  const line = (type, coordinates, pointType = "2") =>
    m.createEntityFromAttributes("LSG", { LineStringType: type, Point: coordinates.map((c) => point(pointType, c)) });
  const partfields = parcels.map((f) => {
    const rings = f.geometry.coordinates;
    const boundary = m.createEntityFromAttributes("PLN", {
      PolygonType: "1",
      LineString: rings.map((r, i) => line(i === 0 ? "1" : "2", r)),
    });
    const [a, b] = rings[0];
    const ab = m.createEntityFromAttributes("LSG", { LineStringType: "5", Point: [point("6", a), point("7", b)] });
    const attrs = {
      PartfieldDesignator: f.properties.id,
      PartfieldArea: Math.round(f.properties.area_ha * 10_000),
      PolygonnonTreatmentZoneonly: [boundary],
    };
    if (version === 4) {
      const pattern = m.createEntityFromAttributes("GPN", { GuidancePatternType: "1", LineString: [ab] });
      m.registerEntity(pattern);
      const group = m.createEntityFromAttributes("GGP", { GuidancePattern: [pattern] });
      m.registerEntity(group);
      attrs.GuidanceGroup = [group];
    } else {
      attrs.LineString = [ab];
    }
    const pfd = m.createEntityFromAttributes("PFD", attrs);
    m.registerEntity(pfd);
    return pfd;
  });
  m.rootElement.attributes.Partfield = partfields;
  return m.saveISOXML();
}

writeFileSync(new URL("dk_marker_taskdata_v4.zip", out), await taskdata("dk_marker_2026_sample.geojson", 4));
writeFileSync(new URL("nl_brp_taskdata_v3.zip", out), await taskdata("nl_brp_2023_sample.geojson", 3));
console.log("tests/format-fixtures: dk_marker_taskdata_v4.zip, nl_brp_taskdata_v3.zip");
