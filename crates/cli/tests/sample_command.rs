//! `lambert sample`: the interface external checkers rely on.

use std::process::Command;

fn lambert(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_lambert"))
        .args(args)
        .output()
        .expect("the lambert binary runs")
}

fn triples(bytes: &[u8]) -> Vec<[f32; 3]> {
    bytes
        .chunks_exact(12)
        .map(|c| {
            let f = |k: usize| f32::from_le_bytes(c[4 * k..4 * k + 4].try_into().unwrap());
            [f(0), f(1), f(2)]
        })
        .collect()
}

#[test]
fn writes_n_unit_f32le_triples_deterministically() {
    for precision in ["f32", "f64"] {
        let args = [
            "sample",
            "cosine-hemisphere",
            "--n",
            "500",
            "--seed",
            "7",
            "--format",
            "f32le",
            "--precision",
            precision,
        ];
        let a = lambert(&args);
        assert!(a.status.success());
        assert_eq!(a.stdout.len(), 500 * 12);
        for [x, y, z] in triples(&a.stdout) {
            // Unit to f32 rounding of each component (3 roundings + the
            // warp's own): 1e-6 is ~8 ulps of 1.
            assert!(((x * x + y * y + z * z).sqrt() - 1.0).abs() < 1e-6);
            assert!(z > 0.0);
        }
        assert_eq!(lambert(&args).stdout, a.stdout, "same seed, same bytes");
        let mut other = args;
        other[4] = "8";
        assert_ne!(lambert(&other).stdout, a.stdout, "another seed differs");
    }
}

#[test]
fn csv_and_every_named_warp() {
    let cases: &[&[&str]] = &[
        &["uniform-hemisphere"],
        &["cosine-hemisphere"],
        &["uniform-sphere"],
        &["uniform-cone", "--cos-theta-max", "0.9"],
        &["uniform-cone", "--cos-theta-max", "-0.5"],
        &["sphere-light", "--center", "0,5,8.66", "--radius", "1"],
        &[
            "spherical-triangle",
            "--vertices",
            "-1,-1,3;2,-0.5,3.5;0,1.5,2.5",
        ],
        &[
            "spherical-rectangle",
            "--corner",
            "-0.5,-0.3,2",
            "--edge0",
            "1,0,0",
            "--edge1",
            "0,0.8,0",
        ],
    ];
    for case in cases {
        let mut args = vec!["sample"];
        args.extend_from_slice(case);
        args.extend_from_slice(&["--n", "20", "--format", "csv"]);
        let out = lambert(&args);
        assert!(
            out.status.success(),
            "{case:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        assert_eq!(text.lines().count(), 20, "{case:?}");
        for line in text.lines() {
            let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
            assert_eq!(v.len(), 3);
        }
    }
}

#[test]
fn tiny_cone_survives_the_f32_path() {
    // θmax = 1e-5 rad: cos θmax = 1 − 5e-11 rounds to 1 in f32, yet the f32
    // path must sample inside the cone and not collapse onto the axis.
    let c = format!("{:.17}", (1e-5f64).cos());
    let out = lambert(&[
        "sample",
        "uniform-cone",
        "--cos-theta-max",
        &c,
        "--n",
        "2000",
        "--precision",
        "f32",
    ]);
    assert!(out.status.success());
    let mut max_offset: f64 = 0.0;
    for [x, y, _] in triples(&out.stdout) {
        let lateral = ((x as f64).powi(2) + (y as f64).powi(2)).sqrt();
        // Inside the cone, to f32's relative precision on x and y.
        assert!(lateral <= 1e-5 * (1.0 + 1e-6), "lateral {lateral:e}");
        max_offset = max_offset.max(lateral);
    }
    // 2000 uniform samples of the cap reach beyond 0.99 θmax with
    // probability 1 − (0.99²)^2000 ≈ 1 − 4e-18.
    assert!(max_offset > 0.99e-5, "max lateral offset {max_offset:e}");
}

#[test]
fn bad_parameters_exit_2_with_a_clear_message() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["uniform-cone", "--cos-theta-max", "1.5"],
            "--cos-theta-max",
        ),
        (&["uniform-cone", "--cos-theta-max", "NaN"], "cos-theta-max"),
        (
            &["sphere-light", "--center", "0,0,0.5", "--radius", "1"],
            "inside",
        ),
        (
            &["sphere-light", "--center", "0,0", "--radius", "1"],
            "--center",
        ),
        (
            &["sphere-light", "--center", "0,0,5", "--radius", "-1"],
            "radius",
        ),
        (
            &["spherical-triangle", "--vertices", "0,0,1;1,0,1"],
            "--vertices",
        ),
        (
            &["spherical-triangle", "--vertices", "0,0,1;1,0,1;2,0,1"],
            "degenerate",
        ),
        (
            &[
                "spherical-rectangle",
                "--corner",
                "0,0,1",
                "--edge0",
                "1,0,0",
                "--edge1",
                "1,1,0",
            ],
            "perpendicular",
        ),
        (&["no-such-warp"], "no-such-warp"),
        (&["uniform-sphere", "--format", "xml"], "xml"),
        (&["uniform-sphere", "--n", "-3"], "-3"),
    ];
    for (case, needle) in cases {
        let mut args = vec!["sample"];
        args.extend_from_slice(case);
        let out = lambert(&args);
        assert_eq!(out.status.code(), Some(2), "{case:?}");
        assert!(out.stdout.is_empty(), "{case:?}: nothing half-written");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{case:?}: {err}");
    }
}
