//! `lambert sample WARP [params] --n N --seed S --format f32le|csv`: writes N
//! unit directions drawn by one warp to standard output, for external
//! checkers. The interface is fixed (see issue 2); keep it exactly so.

use std::io::{self, BufWriter, Write};

use clap::{Args, Subcommand, ValueEnum};
use glam::DVec3;
use lambert_sampling::sequence::{Independent, SampleSequence};
use lambert_validate::catalog::{DirectionWarpSpec, Precision};

use crate::parse;

/// Options shared by every warp.
#[derive(Args, Debug, Clone)]
pub struct SampleOptions {
    /// Number of directions to write.
    #[arg(long = "n", global = true, default_value_t = 1000)]
    pub n: u64,
    /// Seed of the random sequence (the same seed gives the same output).
    #[arg(long, global = true, default_value_t = 0)]
    pub seed: u64,
    /// Output format: little-endian f32 triples, or CSV lines "x,y,z".
    #[arg(long, global = true, value_enum, default_value_t = Format::F32le)]
    pub format: Format,
    /// Which implementation of the warp to run.
    #[arg(long, global = true, value_enum, default_value_t = PrecisionArg::F64)]
    pub precision: PrecisionArg,
}

/// Output encodings.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Little-endian IEEE f32 x, y, z per direction (12 bytes each).
    F32le,
    /// One "x,y,z" line per direction, shortest round-trip decimals.
    Csv,
}

/// The precision flag.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrecisionArg {
    /// The f32 implementation.
    F32,
    /// The f64 implementation.
    F64,
}

/// The warp to sample, with its parameters.
#[derive(Subcommand, Debug, Clone)]
pub enum WarpCommand {
    /// Uniform on the hemisphere about +z (pdf 1/2π).
    UniformHemisphere,
    /// Cosine-weighted about +z (pdf cos θ/π).
    CosineHemisphere,
    /// Uniform on the sphere (pdf 1/4π).
    UniformSphere,
    /// Uniform in the cone about +z with the given cos θmax.
    UniformCone {
        /// cos θmax ∈ [-1, 1). Parsed in f64; the f32 path receives
        /// 1 − cos θmax, so tiny cones keep their size.
        #[arg(long = "cos-theta-max", allow_negative_numbers = true)]
        cos_theta_max: f64,
    },
    /// Solid-angle sampling of a sphere seen from the origin.
    SphereLight {
        /// Center X,Y,Z.
        #[arg(long, allow_hyphen_values = true)]
        center: String,
        /// Radius (> 0, smaller than the center's distance).
        #[arg(long)]
        radius: f64,
    },
    /// Uniform in the spherical triangle a triangle subtends at the origin.
    SphericalTriangle {
        /// Three vertices "X,Y,Z;X,Y,Z;X,Y,Z".
        #[arg(long, allow_hyphen_values = true)]
        vertices: String,
    },
    /// Uniform in the spherical rectangle a rectangle subtends at the origin.
    SphericalRectangle {
        /// One corner X,Y,Z.
        #[arg(long, allow_hyphen_values = true)]
        corner: String,
        /// First edge X,Y,Z from the corner.
        #[arg(long, allow_hyphen_values = true)]
        edge0: String,
        /// Second edge X,Y,Z, perpendicular to the first.
        #[arg(long, allow_hyphen_values = true)]
        edge1: String,
    },
}

impl WarpCommand {
    /// The validated warp description.
    pub fn spec(&self) -> Result<DirectionWarpSpec, String> {
        Ok(match self {
            WarpCommand::UniformHemisphere => DirectionWarpSpec::UniformHemisphere,
            WarpCommand::CosineHemisphere => DirectionWarpSpec::CosineHemisphere,
            WarpCommand::UniformSphere => DirectionWarpSpec::UniformSphere,
            WarpCommand::UniformCone { cos_theta_max } => {
                let c = parse::finite("cos-theta-max", *cos_theta_max)?;
                if !(-1.0..1.0).contains(&c) {
                    return Err(format!("--cos-theta-max: must lie in [-1, 1), got {c}"));
                }
                // Exact for c ≥ ½ (Sterbenz): no loss for small cones.
                DirectionWarpSpec::UniformCone {
                    one_minus_cos_theta_max: 1.0 - c,
                }
            }
            WarpCommand::SphereLight { center, radius } => DirectionWarpSpec::SphereLight {
                center: parse::vec3("center", center)?,
                radius: parse::finite("radius", *radius)?,
            },
            WarpCommand::SphericalTriangle { vertices } => {
                let v = parse::vec3_list("vertices", vertices, 3)?;
                DirectionWarpSpec::SphericalTriangle {
                    vertices: [v[0], v[1], v[2]],
                }
            }
            WarpCommand::SphericalRectangle {
                corner,
                edge0,
                edge1,
            } => DirectionWarpSpec::SphericalRectangle {
                corner: parse::vec3("corner", corner)?,
                edge0: parse::vec3("edge0", edge0)?,
                edge1: parse::vec3("edge1", edge1)?,
            },
        })
    }
}

/// Runs the command; `Err` carries a message for the user (exit code 2).
pub fn run(warp: &WarpCommand, options: &SampleOptions) -> Result<(), String> {
    let spec = warp.spec()?;
    let precision = match options.precision {
        PrecisionArg::F32 => Precision::F32,
        PrecisionArg::F64 => Precision::F64,
    };
    let sampler = spec
        .build(precision)
        .map_err(|e| format!("{}: {e}", spec.name()))?;
    let stdout = io::stdout();
    let mut out = BufWriter::with_capacity(1 << 16, stdout.lock());
    // Sample i reads its own PCG stream (random access by index), so the
    // output for a seed never depends on how it is consumed.
    let mut sequence = Independent::new(options.seed);
    let write = |out: &mut BufWriter<_>, w: DVec3| -> io::Result<()> {
        match options.format {
            Format::F32le => {
                let mut buf = [0u8; 12];
                for (k, c) in w.as_vec3().to_array().into_iter().enumerate() {
                    buf[4 * k..4 * k + 4].copy_from_slice(&c.to_le_bytes());
                }
                out.write_all(&buf)
            }
            Format::Csv => {
                let w = w.as_vec3();
                writeln!(out, "{},{},{}", w.x, w.y, w.z)
            }
        }
    };
    for i in 0..options.n {
        sequence.start_sample(i);
        // The f32 path gets 24-bit uniforms, exactly representable in f32.
        let u = match precision {
            Precision::F32 => sequence.next_2d_f32().as_dvec2(),
            Precision::F64 => sequence.next_2d(),
        };
        let w = sampler.sample(u).direction;
        if let Err(e) = write(&mut out, w) {
            return broken_pipe_is_fine(e);
        }
    }
    out.flush().or_else(broken_pipe_is_fine)
}

/// A reader that stops early (`| head`) is not an error.
fn broken_pipe_is_fine(e: io::Error) -> Result<(), String> {
    if e.kind() == io::ErrorKind::BrokenPipe {
        Ok(())
    } else {
        Err(format!("writing samples: {e}"))
    }
}
