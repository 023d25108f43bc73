//! OpenEXR output reads back bit-exact (every layer), the PNG preview is
//! written beside it, and a failed write leaves nothing behind.

use std::path::PathBuf;

use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::point::PointConfig;
use lambert_estimator::strategy::Strategy;
use lambert_tracer::output::{read_exr, write_outputs};
use lambert_tracer::{builtin, render, Mode, RenderConfig};

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("lambert-tracer-{name}-{}.exr", std::process::id()))
}

#[test]
fn exr_files_read_back_bit_exact() {
    let scene = builtin::cornell().with_size(20, 16).unwrap();
    let config = RenderConfig {
        mode: Mode::Irradiance,
        estimate: PointConfig {
            strategy: Strategy::Light,
            sequence: SequenceKind::Independent,
            samples: 8,
            seed: 5,
        },
        ..RenderConfig::default()
    };
    let image = render(&scene, &config, &|_, _| {}).unwrap().image;
    assert!(image.std_error_layer().is_some());
    let path = temp("roundtrip");
    let (exr, png) = write_outputs(&image, &path).unwrap();
    let back = read_exr(&exr).unwrap();
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(back.width(), 20);
    assert_eq!(back.height(), 16);
    assert_eq!(
        bits(back.rgb_layer().as_flattened()),
        bits(image.rgb_layer().as_flattened())
    );
    assert_eq!(
        bits(back.irradiance_layer()),
        bits(image.irradiance_layer())
    );
    assert_eq!(
        bits(back.std_error_layer().unwrap()),
        bits(image.std_error_layer().unwrap())
    );
    let preview = std::fs::read(&png).unwrap();
    assert_eq!(&preview[..8], b"\x89PNG\r\n\x1a\n");
    // Nothing temporary is left beside them.
    let dir = exr.parent().unwrap();
    let stem = exr.file_name().unwrap().to_string_lossy().to_string();
    let leftovers = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| {
            let n = e.file_name().to_string_lossy().to_string();
            n.starts_with(&stem) && n.contains(".tmp-")
        })
        .count();
    assert_eq!(leftovers, 0);
    let _ = std::fs::remove_file(&exr);
    let _ = std::fs::remove_file(&png);

    // A whitted-mode image has no standard-error layer.
    let w = render(
        &builtin::whitted().with_size(8, 8).unwrap(),
        &RenderConfig::default(),
        &|_, _| {},
    )
    .unwrap()
    .image;
    let path = temp("roundtrip-whitted");
    let (exr, png) = write_outputs(&w, &path).unwrap();
    assert_eq!(read_exr(&exr).unwrap(), w);
    let _ = std::fs::remove_file(&exr);
    let _ = std::fs::remove_file(&png);
}

#[test]
fn a_failed_write_leaves_nothing() {
    let image = render(
        &builtin::whitted().with_size(4, 4).unwrap(),
        &RenderConfig::default(),
        &|_, _| {},
    )
    .unwrap()
    .image;
    let missing = std::env::temp_dir()
        .join(format!("lambert-no-such-dir-{}", std::process::id()))
        .join("out.exr");
    let e = write_outputs(&image, &missing).unwrap_err();
    assert_eq!(e.field, "--out");
    assert!(!missing.exists());
}
