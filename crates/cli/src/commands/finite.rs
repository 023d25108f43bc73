//! Numbers the commands print must be finite. An irradiance beyond the f64
//! range (a sky of radiance 1e308 has E = π·1e308, which overflows), a sum
//! of emitters that overflows, or a comparison ratio that overflows is an
//! error naming the emitter (or the JSON key) and the quantity, with exit
//! code 2 — never a JSON `null` with exit code 0. A NaN where the inputs
//! were valid is lambert's fault, and the message says so.

use lambert_light::Emitter;

/// The largest finite f64, as the messages quote it.
const F64_MAX: &str = "≈ 1.8e308";

/// How a message marks a defect of lambert (not of the scene).
pub const DEFECT: &str =
    "this is a defect in lambert, not in the scene: please report it with this scene file";

/// The field that sets an emitter's strength, and its value: `radiance`
/// for the area lights and skies, `intensity` for a point light (a `flux`
/// given in the file is stored as the intensity Φ/4π), `irradiance` for a
/// directional light.
pub fn strength(e: &Emitter) -> (&'static str, f64) {
    match e {
        Emitter::Sky(s) => ("radiance", s.radiance),
        Emitter::SkyCap(c) => ("radiance", c.radiance),
        Emitter::Sphere(s) => ("radiance", s.radiance),
        Emitter::Disk(d) => ("radiance", d.radiance),
        Emitter::Polygon(p) => ("radiance", p.radiance),
        Emitter::Point(p) => ("intensity", p.intensity),
        Emitter::Directional(d) => ("irradiance", d.irradiance),
    }
}

/// `emitters[i] (kind, field = value)`: how messages name an emitter.
pub fn describe(i: usize, e: &Emitter) -> String {
    let (field, value) = strength(e);
    format!("emitters[{i}] ({}, {field} = {value:e})", e.kind())
}

/// Emitter `i`'s irradiance `value` (closed form, or exact for a delta
/// light), if finite; an overflow names the emitter and its strength, a
/// NaN is reported as a defect.
pub fn emitter_irradiance(i: usize, e: &Emitter, value: f64) -> Result<f64, String> {
    if value.is_finite() {
        return Ok(value);
    }
    let (field, strength) = strength(e);
    if value.is_nan() {
        Err(format!(
            "emitters[{i}] ({}): its closed-form irradiance came out NaN; {DEFECT}",
            e.kind()
        ))
    } else {
        Err(format!(
            "emitters[{i}].{field}: the irradiance of this {} emitter overflows: with {field} = {strength:e} it exceeds the largest finite f64 ({F64_MAX} W/m²)",
            e.kind()
        ))
    }
}

/// Σ `values` (left to right, as the JSON's `per_emitter` adds up), if
/// finite; an overflowing sum names the emitters that contribute.
pub fn total(emitters: &[Emitter], values: &[f64]) -> Result<f64, String> {
    let sum: f64 = values.iter().sum();
    if sum.is_finite() {
        return Ok(sum);
    }
    let parts: Vec<String> = emitters
        .iter()
        .zip(values)
        .enumerate()
        .filter(|(_, (_, v))| **v > 0.0)
        .map(|(i, (e, v))| format!("emitters[{i}] ({}) {v:e}", e.kind()))
        .collect();
    Err(format!(
        "irradiance: each emitter's irradiance is finite but their sum overflows the f64 range ({F64_MAX} W/m²): {} W/m²",
        parts.join(" + ")
    ))
}

/// A derived quantity of the estimate's output (`rel_error`, `z`), if
/// finite; otherwise an error naming the JSON key and the ratio.
pub fn ratio(key: &str, what: &str, numerator: f64, denominator: f64) -> Result<f64, String> {
    let r = numerator / denominator;
    if r.is_finite() {
        Ok(r)
    } else {
        Err(format!(
            "{key}: the {what} {numerator:e}/{denominator:e} is not a finite f64 (the estimate and the closed form disagree beyond the f64 range)"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use lambert_light::emitter::{PointLight, Sky};

    #[test]
    fn overflow_names_the_emitter_and_the_quantity() {
        let sky = Emitter::Sky(Sky::new(1e308).unwrap());
        let e = emitter_irradiance(2, &sky, f64::INFINITY).unwrap_err();
        assert!(e.starts_with("emitters[2].radiance:"), "{e}");
        assert!(e.contains("irradiance") && e.contains("1e308"), "{e}");
        let nan = emitter_irradiance(0, &sky, f64::NAN).unwrap_err();
        assert!(
            nan.contains("emitters[0]") && nan.contains("defect"),
            "{nan}"
        );
        assert_eq!(emitter_irradiance(0, &sky, 3.0), Ok(3.0));
    }

    #[test]
    fn an_overflowing_sum_names_every_contributor() {
        let point = Emitter::Point(PointLight::with_intensity(DVec3::Z, 1e308).unwrap());
        let sky = Emitter::Sky(Sky::new(1e300).unwrap());
        let e = total(&[point, sky], &[1.7e308, 1.7e308]).unwrap_err();
        assert!(e.starts_with("irradiance:"), "{e}");
        assert!(
            e.contains("emitters[0] (point)") && e.contains("emitters[1] (sky)"),
            "{e}"
        );
        assert_eq!(total(&[], &[]), Ok(0.0));
    }

    #[test]
    fn ratios() {
        assert_eq!(ratio("z", "z-score", 1.0, 2.0), Ok(0.5));
        let e = ratio("rel_error", "relative error", 1e-10, 5e-324).unwrap_err();
        assert!(e.starts_with("rel_error:"), "{e}");
    }
}
