//! The coordinate reference systems a field file may come in, and their conversion to WGS84
//! longitude and latitude.
//!
//! A Shapefile's `.prj` is WKT, most often in ESRI's dialect, and names its system without the
//! datum shift: Dutch RD New comes on the Bessel ellipsoid without its shift to WGS84, which
//! puts a field about 114 m from where it is, with no error, in every reader that converts
//! what the WKT says. So the system is first identified (its EPSG code where the WKT has one,
//! else its name) and converted by a definition of furrow's own, with the shift its national
//! mapping agency publishes: WGS84 and ETRS89 longitude and latitude, UTM on either, RD New
//! (the Netherlands, EPSG's 7-parameter transformation 4833, good to a metre), ETRS-TM35FIN
//! (Finland). ETRS89 and WGS84 differ by under a metre and are taken as one, as every library
//! does. A system it does not know is refused with `unknown_crs`, naming it.
//!
//! ```
//! use furrow::formats::crs::Crs;
//!
//! let prj = r#"PROJCS["ETRS_1989_UTM_Zone_32N",GEOGCS["GCS_ETRS_1989",DATUM["D_ETRS_1989",
//!     SPHEROID["GRS_1980",6378137.0,298.257222101]],PRIMEM["Greenwich",0.0],
//!     UNIT["Degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],
//!     PARAMETER["False_Easting",500000.0],PARAMETER["Central_Meridian",9.0],
//!     PARAMETER["Scale_Factor",0.9996],UNIT["Meter",1.0]]"#;
//! let crs = Crs::from_wkt(prj)?;
//! assert_eq!(crs.epsg, 25832);
//! // The central meridian, on the equator.
//! let [lon, lat] = crs.to_wgs84(&[[500_000.0, 0.0]])?[0];
//! assert!((lon - 9.0).abs() < 1e-9 && lat.abs() < 1e-9);
//! # Ok::<(), furrow::PlanError>(())
//! ```

use crate::error::{ErrorCode, PlanError};
use proj4rs::proj::Proj;

/// A coordinate reference system furrow converts from.
#[derive(Debug, Clone)]
pub struct Crs {
    /// Its EPSG code.
    pub epsg: u32,
    /// Its name, for messages and the result (`"Amersfoort / RD New"`).
    pub name: String,
    proj: Proj,
}

/// The systems known by code, with their PROJ definitions (datum shifts included).
fn definition(epsg: u32) -> Option<(String, String)> {
    let utm = |zone: u32, south: bool, datum: &str| {
        format!(
            "+proj=utm +zone={zone}{} {datum} +units=m",
            if south { " +south" } else { "" }
        )
    };
    const GRS80: &str = "+ellps=GRS80 +towgs84=0,0,0";
    let known = match epsg {
        4326 => ("WGS 84".into(), "+proj=longlat +datum=WGS84".into()),
        4258 => ("ETRS89".into(), format!("+proj=longlat {GRS80}")),
        // EPSG's transformation 4833, Amersfoort to WGS 84 (4), in PROJ's position-vector
        // convention (the rotations of EPSG's coordinate-frame parameters negated).
        28992 => (
            "Amersfoort / RD New".into(),
            "+proj=sterea +lat_0=52.1561605555556 +lon_0=5.38763888888889 +k=0.9999079 \
             +x_0=155000 +y_0=463000 +ellps=bessel \
             +towgs84=565.4171,50.3319,465.5524,-0.398957388243134,0.343987817378283,-1.87740163998045,4.0725 \
             +units=m"
                .into(),
        ),
        3067 => ("ETRS89 / TM35FIN(E,N)".into(), utm(35, false, GRS80)),
        25828..=25838 => (
            format!("ETRS89 / UTM zone {}N", epsg - 25800),
            utm(epsg - 25800, false, GRS80),
        ),
        32601..=32660 => (
            format!("WGS 84 / UTM zone {}N", epsg - 32600),
            utm(epsg - 32600, false, "+datum=WGS84"),
        ),
        32701..=32760 => (
            format!("WGS 84 / UTM zone {}S", epsg - 32700),
            utm(epsg - 32700, true, "+datum=WGS84"),
        ),
        _ => return None,
    };
    Some(known)
}

impl Crs {
    /// The system of EPSG code `epsg`, if furrow knows it.
    pub fn from_epsg(epsg: u32) -> Result<Crs, PlanError> {
        let (name, definition) = definition(epsg).ok_or_else(|| {
            PlanError::new(
                ErrorCode::UnknownCrs,
                format!("the coordinate system EPSG:{epsg} is not one furrow can convert from (it knows WGS 84 and ETRS89 longitude and latitude, UTM on either, RD New and TM35FIN); export the field in WGS 84"),
            )
        })?;
        let proj = Proj::from_proj_string(&definition).map_err(|e| {
            PlanError::new(
                ErrorCode::Internal,
                format!("the definition of EPSG:{epsg} does not load: {e}"),
            )
        })?;
        Ok(Crs { epsg, name, proj })
    }

    /// The system a WKT text names (a Shapefile's `.prj`: WKT 1 in OGC's or ESRI's dialect, or
    /// WKT 2): by the EPSG code of its outermost system where it has one, else by its name.
    pub fn from_wkt(wkt: &str) -> Result<Crs, PlanError> {
        let name = outer_name(wkt);
        let epsg = outer_epsg(wkt).or_else(|| name.as_deref().and_then(epsg_of_name));
        match epsg {
            Some(code) => Crs::from_epsg(code),
            None => Err(PlanError::new(
                ErrorCode::UnknownCrs,
                format!(
                    "the coordinate system {} is not one furrow can convert from (it knows WGS 84 and ETRS89 longitude and latitude, UTM on either, RD New and TM35FIN); export the field in WGS 84",
                    name.map_or_else(|| "of the .prj file".to_string(), |n| format!("\"{n}\""))
                ),
            )),
        }
    }

    /// Whether the system's coordinates are longitude and latitude in degrees.
    pub fn is_geographic(&self) -> bool {
        self.proj.is_latlong()
    }

    /// `points` (x, y in the system; longitude, latitude in degrees for a geographic one) as
    /// WGS84 longitude and latitude in degrees.
    pub fn to_wgs84(&self, points: &[[f64; 2]]) -> Result<Vec<[f64; 2]>, PlanError> {
        if self.epsg == 4326 {
            return Ok(points.to_vec());
        }
        let wgs84 = wgs84()?;
        let geographic = self.is_geographic();
        let mut out = Vec::with_capacity(points.len());
        for &[x, y] in points {
            let mut p = if geographic {
                (x.to_radians(), y.to_radians(), 0.0)
            } else {
                (x, y, 0.0)
            };
            proj4rs::transform::transform(&self.proj, &wgs84, &mut p).map_err(|_| {
                PlanError::new(
                    ErrorCode::CoordinateOutOfRange,
                    format!(
                        "the point ({x}, {y}) cannot be converted from {} to longitude and latitude: it lies outside the system's area",
                        self.name
                    ),
                )
            })?;
            let (lon, lat) = (p.0.to_degrees(), p.1.to_degrees());
            if !(lon.is_finite() && lat.is_finite()) {
                return Err(PlanError::new(
                    ErrorCode::NonFiniteCoordinate,
                    format!(
                        "the point ({x}, {y}) in {} has no longitude and latitude",
                        self.name
                    ),
                ));
            }
            out.push([lon, lat]);
        }
        Ok(out)
    }
}

fn wgs84() -> Result<Proj, PlanError> {
    Proj::from_proj_string("+proj=longlat +datum=WGS84")
        .map_err(|e| PlanError::new(ErrorCode::Internal, format!("WGS 84 does not load: {e}")))
}

/// The name of the outermost system: the first quoted text of the WKT.
fn outer_name(wkt: &str) -> Option<String> {
    let start = wkt.find('"')? + 1;
    let len = wkt[start..].find('"')?;
    Some(wkt[start..start + len].to_string())
}

/// The EPSG code of the outermost system: WKT 1 puts its `AUTHORITY["EPSG","28992"]` last,
/// WKT 2 its `ID["EPSG",28992]`.
fn outer_epsg(wkt: &str) -> Option<u32> {
    let upper = wkt.to_ascii_uppercase();
    let at = upper.rfind("AUTHORITY[").or_else(|| upper.rfind("ID["))?;
    // Only the outermost system's: nothing but closing brackets after it.
    let tail = &wkt[at..];
    let close = tail.find(']')?;
    if !tail[close..].chars().all(|c| c == ']' || c.is_whitespace()) {
        return None;
    }
    let inner = &tail[..close];
    if !inner.to_ascii_uppercase().contains("\"EPSG\"") {
        return None;
    }
    let code: String = inner
        .rsplit(',')
        .next()?
        .chars()
        .filter(char::is_ascii_digit)
        .collect();
    code.parse().ok()
}

/// The EPSG code of a system by the names GIS software writes for it (ESRI's and OGC's
/// spellings alike: letters and digits compared, case and punctuation ignored).
fn epsg_of_name(name: &str) -> Option<u32> {
    let key: String = name
        .chars()
        .filter(char::is_ascii_alphanumeric)
        .collect::<String>()
        .to_ascii_lowercase();
    let fixed = match key.as_str() {
        "gcswgs1984" | "wgs84" | "wgs1984" => Some(4326),
        "gcsetrs1989" | "etrs89" | "etrs1989" => Some(4258),
        "rdnew" | "amersfoortrdnew" => Some(28992),
        "eureffintm35fin"
        | "etrstm35fin"
        | "etrs89tm35fin"
        | "etrs89etrstm35fin"
        | "etrs89etrstm35finen"
        | "etrs89tm35finen" => Some(3067),
        _ => None,
    };
    fixed.or_else(|| utm_of_name(&key))
}

/// UTM zones by name: `ETRS_1989_UTM_Zone_32N`, `ETRS89 / UTM zone 32N`,
/// `WGS_1984_UTM_Zone_33S`, `WGS 84 / UTM zone 33S`.
fn utm_of_name(key: &str) -> Option<u32> {
    let (datum, rest) = if let Some(r) = key.strip_prefix("etrs1989utmzone") {
        (25800, r)
    } else if let Some(r) = key.strip_prefix("etrs89utmzone") {
        (25800, r)
    } else if let Some(r) = key.strip_prefix("wgs1984utmzone") {
        (32600, r)
    } else if let Some(r) = key.strip_prefix("wgs84utmzone") {
        (32600, r)
    } else {
        return None;
    };
    let (zone, hemisphere) = rest.split_at(rest.len().checked_sub(1)?);
    let zone: u32 = zone.parse().ok().filter(|z| (1..=60).contains(z))?;
    match (datum, hemisphere) {
        (25800, "n") => Some(25800 + zone),
        (32600, "n") => Some(32600 + zone),
        (32600, "s") => Some(32700 + zone),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rd_new_without_its_shift_in_the_prj_is_converted_with_it() {
        // The Amersfoort origin: with the 7-parameter shift 5.3872036, 52.1551723 (PROJ 9,
        // transformation 4833); without it about 114 m away, at 5.3876389, 52.1561606.
        let esri = r#"PROJCS["RD_New",GEOGCS["GCS_Amersfoort",DATUM["D_Amersfoort",SPHEROID["Bessel_1841",6377397.155,299.1528128]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],PROJECTION["Double_Stereographic"],PARAMETER["False_Easting",155000.0],PARAMETER["False_Northing",463000.0],PARAMETER["Central_Meridian",5.38763888888889],PARAMETER["Scale_Factor",0.9999079],PARAMETER["Latitude_Of_Origin",52.1561605555556],UNIT["Meter",1.0]]"#;
        let crs = Crs::from_wkt(esri).unwrap();
        assert_eq!(crs.epsg, 28992);
        let [lon, lat] = crs.to_wgs84(&[[155_000.0, 463_000.0]]).unwrap()[0];
        // Within 1e-7 degrees (a centimetre) of PROJ's.
        assert!((lon - 5.3872036).abs() < 1e-7, "{lon}");
        assert!((lat - 52.1551723).abs() < 1e-7, "{lat}");
    }

    #[test]
    fn systems_are_known_by_code_and_by_name() {
        let ogc = r#"PROJCS["Amersfoort / RD New",GEOGCS["Amersfoort",AUTHORITY["EPSG","4289"]],UNIT["metre",1,AUTHORITY["EPSG","9001"]],AUTHORITY["EPSG","28992"]]"#;
        assert_eq!(Crs::from_wkt(ogc).unwrap().epsg, 28992);
        let wkt2 = r#"PROJCRS["ETRS89 / TM35FIN(E,N)",BASEGEOGCRS["ETRS89"],ID["EPSG",3067]]"#;
        assert_eq!(Crs::from_wkt(wkt2).unwrap().epsg, 3067);
        for (name, code) in [
            ("EUREF_FIN_TM35FIN", 3067),
            ("WGS_1984_UTM_Zone_33S", 32733),
            ("WGS 84 / UTM zone 31N", 32631),
            ("ETRS89 / UTM zone 33N", 25833),
            ("GCS_WGS_1984", 4326),
        ] {
            let wkt = format!(r#"PROJCS["{name}",GEOGCS["x"]]"#);
            assert_eq!(Crs::from_wkt(&wkt).unwrap().epsg, code, "{name}");
        }
    }

    #[test]
    fn an_unknown_system_is_refused_by_name() {
        let e = Crs::from_wkt(
            r#"PROJCS["DHDN_3_Degree_Gauss_Zone_3",GEOGCS["GCS_Deutsches_Hauptdreiecksnetz"]]"#,
        )
        .unwrap_err();
        assert_eq!(e.code, ErrorCode::UnknownCrs);
        assert!(
            e.message.contains("DHDN_3_Degree_Gauss_Zone_3"),
            "{}",
            e.message
        );
        assert_eq!(Crs::from_wkt("").unwrap_err().code, ErrorCode::UnknownCrs);
        assert_eq!(
            Crs::from_epsg(2056).unwrap_err().code,
            ErrorCode::UnknownCrs
        );
    }
}
