/** A field file read: its parcels as a GeoJSON FeatureCollection in WGS84, each a Polygon
 * Feature with the file's attributes as properties (and `part` where a record held several). */
export interface FieldFileGeoJson {
  type: "FeatureCollection";
  /** What was read: the format and the coordinate system converted from. */
  source: { format: "shapefile" | "kml" | "kmz"; crs: string };
  features: Array<{
    type: "Feature";
    properties: Record<string, string | number | boolean>;
    geometry: { type: "Polygon"; coordinates: number[][][] };
  }>;
}
