/** A field file read: its parcels as a GeoJSON FeatureCollection in WGS84, each a Polygon
 * Feature with the file's attributes as properties (and `part` where a record held several). */
export interface FieldFileGeoJson {
  type: "FeatureCollection";
  /** What was read: the format and the coordinate system converted from. */
  source: { format: "shapefile" | "kml" | "kmz" | "isoxml"; crs: string };
  features: Array<
    | {
        type: "Feature";
        /** The file's attributes; from TaskData also `guidance` (each AB line and curve of the
         * partfield) and `reference_line` (its first AB line, [A, B]). */
        properties: Record<string, unknown>;
        geometry: { type: "Polygon"; coordinates: number[][][] };
      }
    | {
        /** A file of one TaskData partfield with an AB line: the line, `role: "reference_line"`. */
        type: "Feature";
        properties: { role: "reference_line" };
        geometry: { type: "LineString"; coordinates: number[][] };
      }
  >;
}
