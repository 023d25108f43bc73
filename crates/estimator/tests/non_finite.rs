//! The slow path that names a failed estimate's first non-finite sample,
//! through the crate's public interface.
//!
//! Strength scaling keeps strong emitters from reaching it through
//! `estimate`, so it is called directly on a scene prepared unscaled. It
//! lives here, not beside the code, because it reaches the batch kernels:
//! as a unit test it made the library's test build compile them a second
//! time (about six and a half minutes of the two-core CI machine); from
//! here it links the library's one copy.

use glam::DVec3;
use lambert_estimator::estimation::{
    first_non_finite_in, first_non_finite_independent, prepare, EstimateError,
};
use lambert_estimator::strategy::Strategy;
use lambert_light::emitter::{Emitter, PointLight, Sky};
use lambert_light::receiver::Receiver;
use lambert_light::Scene;
use lambert_sampling::sequence::Sobol;

/// Two skies of radiance 0.9·f64::MAX/π behind a point light (index 0):
/// their cosine samples are π·L each, so every sample's sum overflows at
/// the second sky, emitters[2], from sample 0 on.
fn overflowing_scene() -> (Scene, f64) {
    let radiance = 0.9 * f64::MAX / std::f64::consts::PI;
    let sky = || Emitter::Sky(Sky::new(radiance).unwrap());
    let point = PointLight::with_intensity(DVec3::Z, 1.0).unwrap();
    let receiver = Receiver::new(DVec3::ZERO, DVec3::Z).unwrap();
    let scene = Scene::new(receiver, vec![Emitter::Point(point), sky(), sky()]).unwrap();
    (scene, radiance)
}

/// Sample 0 of emitters[2], a sky, whose value π·L turned the sum to +∞;
/// the randomization is left for the caller (`None`).
fn assert_names_the_second_sky(error: &EstimateError, radiance: f64) {
    match *error {
        EstimateError::NonFiniteSample {
            emitter,
            kind,
            sample,
            randomization,
            value,
            total,
        } => {
            assert_eq!((emitter, kind, sample, randomization), (2, "sky", 0, None));
            // Exact: a cosine sample of a sky is the product π·L, once rounded.
            assert_eq!(value, std::f64::consts::PI * radiance);
            assert_eq!(total, f64::INFINITY);
        }
        ref other => panic!("{other:?}"),
    }
}

#[test]
fn the_first_non_finite_sample_is_named_with_its_emitter() {
    let (scene, radiance) = overflowing_scene();
    let (prepared, _) = prepare(&scene, Strategy::CosineHemisphere);
    let independent = first_non_finite_independent(&prepared, &scene, 1, 8);
    assert_names_the_second_sky(&independent, radiance);
    let sobol = first_non_finite_in(&prepared, &scene, &Sobol::new(1), 8);
    assert_names_the_second_sky(&sobol, radiance);
    // The estimate fills in the randomization; the message names it.
    let mut replicate = sobol;
    if let EstimateError::NonFiniteSample { randomization, .. } = &mut replicate {
        *randomization = Some(3);
    }
    let message = replicate.to_string();
    assert!(
        message.contains("emitters[2] (a sky): sample 0 of randomization 3")
            && message.contains("overflow"),
        "{message}"
    );
}

/// Negative control: where every sample is finite the search reports the
/// fallback, not a sample (one sky of a modest radiance).
#[test]
fn a_finite_estimate_names_no_sample() {
    let receiver = Receiver::new(DVec3::ZERO, DVec3::Z).unwrap();
    let scene = Scene::new(receiver, vec![Emitter::Sky(Sky::new(1.0).unwrap())]).unwrap();
    let (prepared, _) = prepare(&scene, Strategy::CosineHemisphere);
    for error in [
        first_non_finite_independent(&prepared, &scene, 1, 8),
        first_non_finite_in(&prepared, &scene, &Sobol::new(1), 8),
    ] {
        assert!(matches!(error, EstimateError::Overflow { .. }), "{error:?}");
    }
}
