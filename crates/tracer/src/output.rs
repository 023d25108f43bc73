//! Writing images: linear f32 OpenEXR (through the `exr` crate) and a
//! tone-mapped PNG preview beside it, each written to a temporary file and
//! renamed into place, so that a failed run leaves nothing half-written.

use std::path::{Path, PathBuf};

use exr::prelude as x;
use exr::prelude::WritableImage as _;

use crate::error::TracerError;
use crate::image::Image;

/// The EXR channel names: R, G, B (linear radiance), `irradiance.Y` and
/// `std_error.Y` (OpenEXR's layer convention: a layer is a channel-name
/// prefix, so every viewer reads the file as one part).
pub const IRRADIANCE_CHANNEL: &str = "irradiance.Y";
/// See [`IRRADIANCE_CHANNEL`].
pub const STD_ERROR_CHANNEL: &str = "std_error.Y";

/// The PNG preview's path for an EXR path: the same with `.png`.
pub fn preview_path(exr: &Path) -> PathBuf {
    exr.with_extension("png")
}

/// Writes `image` to `path` (OpenEXR, f32, ZIP-compressed, one part with
/// channels R, G, B, `irradiance.Y` and, if present, `std_error.Y`) and the
/// tone-mapped preview to [`preview_path`]`(path)`. Both are written to
/// temporary files in the same directory first and renamed into place only
/// when both are complete. Errors name `--out`.
pub fn write_outputs(image: &Image, path: &Path) -> Result<(PathBuf, PathBuf), TracerError> {
    let png = preview_path(path);
    let tmp_exr = temporary(path);
    let tmp_png = temporary(&png);
    let result = write_exr(image, &tmp_exr)
        .and_then(|()| write_png(image, &tmp_png))
        .and_then(|()| {
            std::fs::rename(&tmp_exr, path).map_err(|e| io("--out", path, e))?;
            std::fs::rename(&tmp_png, &png).map_err(|e| io("--out", &png, e))
        });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp_exr);
        let _ = std::fs::remove_file(&tmp_png);
    }
    result.map(|()| (path.to_path_buf(), png))
}

/// `path` with `.tmp-<pid>` appended to its file name.
fn temporary(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(format!(".tmp-{}", std::process::id()));
    path.with_file_name(name)
}

fn io(field: &str, path: &Path, e: impl std::fmt::Display) -> TracerError {
    TracerError::new(field, format!("cannot write {}: {e}", path.display()))
}

/// Writes the OpenEXR file (see [`write_outputs`]; this writes in place).
pub fn write_exr(image: &Image, path: &Path) -> Result<(), TracerError> {
    let size = (image.width() as usize, image.height() as usize);
    let rgb = image.rgb_layer();
    let channel = |k: usize| rgb.iter().map(|p| p[k]).collect::<Vec<f32>>();
    let mut list: x::SmallVec<[x::AnyChannel<x::FlatSamples>; 4]> = x::SmallVec::new();
    list.push(x::AnyChannel::new("R", x::FlatSamples::F32(channel(0))));
    list.push(x::AnyChannel::new("G", x::FlatSamples::F32(channel(1))));
    list.push(x::AnyChannel::new("B", x::FlatSamples::F32(channel(2))));
    list.push(x::AnyChannel::new(
        IRRADIANCE_CHANNEL,
        x::FlatSamples::F32(image.irradiance_layer().to_vec()),
    ));
    if let Some(se) = image.std_error_layer() {
        list.push(x::AnyChannel::new(
            STD_ERROR_CHANNEL,
            x::FlatSamples::F32(se.to_vec()),
        ));
    }
    let layer = x::Layer::new(
        size,
        x::LayerAttributes::default(),
        x::Encoding::SMALL_LOSSLESS,
        x::AnyChannels::sort(list),
    );
    x::Image::from_layer(layer)
        .write()
        .to_file(path)
        .map_err(|e| io("--out", path, e))
}

/// Reads an OpenEXR file written by [`write_exr`] back into an image.
/// Errors name `path`.
pub fn read_exr(path: &Path) -> Result<Image, TracerError> {
    let err = |m: String| TracerError::new(path.display().to_string(), m);
    let file = x::read_first_flat_layer_from_file(path).map_err(|e| err(e.to_string()))?;
    let layer = &file.layer_data;
    let (w, h) = (layer.size.0 as u32, layer.size.1 as u32);
    let find = |name: &str| -> Option<Vec<f32>> {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == *name)
            .map(|c| c.sample_data.values_as_f32().collect())
    };
    let need = |name: &str| find(name).ok_or_else(|| err(format!("has no channel {name}")));
    let (r, g, b) = (need("R")?, need("G")?, need("B")?);
    let rgb = r
        .iter()
        .zip(&g)
        .zip(&b)
        .map(|((&r, &g), &b)| [r, g, b])
        .collect();
    Image::from_layers(
        w,
        h,
        rgb,
        need(IRRADIANCE_CHANNEL)?,
        find(STD_ERROR_CHANNEL),
    )
    .ok_or_else(|| err("has channels of the wrong length".into()))
}

/// Writes the 8-bit sRGB preview: the radiance tone-mapped by Reinhard et
/// al.'s global operator (2002, "Photographic tone reproduction for
/// digital images": luminance scaled to the key 0.18 of its log-average,
/// then L/(1 + L)), each channel scaled by the luminance's ratio, then
/// encoded with the sRGB transfer function (IEC 61966-2-1).
pub fn write_png(image: &Image, path: &Path) -> Result<(), TracerError> {
    let bytes = tone_map(image);
    let file = std::fs::File::create(path).map_err(|e| io("--out", path, e))?;
    let mut encoder =
        png::Encoder::new(std::io::BufWriter::new(file), image.width(), image.height());
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header().map_err(|e| io("--out", path, e))?;
    writer
        .write_image_data(&bytes)
        .map_err(|e| io("--out", path, e))?;
    writer.finish().map_err(|e| io("--out", path, e))
}

/// The preview's 8-bit sRGB bytes (see [`write_png`]).
pub fn tone_map(image: &Image) -> Vec<u8> {
    let lum = |p: &[f32; 3]| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64;
    let (mut log_sum, mut n) = (0.0f64, 0u64);
    for p in image.rgb_layer() {
        let l = lum(p);
        if l > 0.0 {
            log_sum += (1e-6 + l).ln();
            n += 1;
        }
    }
    let average = if n > 0 {
        (log_sum / n as f64).exp()
    } else {
        1.0
    };
    let scale = 0.18 / average;
    let srgb = |v: f64| {
        let v = v.clamp(0.0, 1.0);
        let e = if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        (e * 255.0 + 0.5) as u8
    };
    let mut out = Vec::with_capacity(image.rgb_layer().len() * 3);
    for p in image.rgb_layer() {
        let l = lum(p);
        let ratio = if l > 0.0 {
            let s = l * scale;
            s / (1.0 + s) / l
        } else {
            0.0
        };
        for &c in p {
            out.push(srgb(c as f64 * ratio));
        }
    }
    out
}
