//! Parsing of vector-valued command-line parameters ("X,Y,Z").

use glam::DVec3;

/// Parses "X,Y,Z" into a vector, naming `field` in the error.
pub fn vec3(field: &str, text: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!(
            "--{field}: expected three comma-separated numbers X,Y,Z, got {text:?}"
        ));
    }
    let mut v = [0.0; 3];
    for (slot, part) in v.iter_mut().zip(&parts) {
        let x: f64 = part
            .parse()
            .map_err(|_| format!("--{field}: {part:?} is not a number (in {text:?})"))?;
        if !x.is_finite() {
            return Err(format!("--{field}: {part:?} is not finite (in {text:?})"));
        }
        *slot = x;
    }
    Ok(DVec3::from_array(v))
}

/// Parses "X,Y,Z;X,Y,Z;…" into exactly `count` vectors.
pub fn vec3_list(field: &str, text: &str, count: usize) -> Result<Vec<DVec3>, String> {
    let items: Vec<&str> = text.split(';').map(str::trim).collect();
    if items.len() != count {
        return Err(format!(
            "--{field}: expected {count} points separated by ';', got {} in {text:?}",
            items.len()
        ));
    }
    items.iter().map(|item| vec3(field, item)).collect()
}

/// Parses `--strategy` and `--sequence` (errors name the option).
pub fn strategy_and_sequence(
    strategy: &str,
    sequence: &str,
) -> Result<
    (
        lambert_estimator::strategy::Strategy,
        lambert_estimator::estimation::SequenceKind,
    ),
    String,
> {
    Ok((
        strategy.parse().map_err(|e| format!("--strategy: {e}"))?,
        sequence.parse().map_err(|e| format!("--sequence: {e}"))?,
    ))
}

/// Parses a finite number, naming `field` in the error.
pub fn finite(field: &str, value: f64) -> Result<f64, String> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(format!("--{field}: must be finite, got {value}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_rejects() {
        assert_eq!(vec3("c", "1, 2,3").unwrap(), DVec3::new(1.0, 2.0, 3.0));
        assert!(vec3("c", "1,2").unwrap_err().contains("--c"));
        assert!(vec3("c", "1,x,3").unwrap_err().contains("\"x\""));
        assert!(vec3("c", "1,NaN,3").unwrap_err().contains("finite"));
        assert_eq!(vec3_list("v", "0,0,1;1,0,1;0,1,1", 3).unwrap().len(), 3);
        assert!(vec3_list("v", "0,0,1;1,0,1", 3).is_err());
    }
}
