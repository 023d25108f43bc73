//! Garbled files: one to three text-level edits of a generated scene, as a
//! bad merge, a truncated write or a hand edit leaves them. Most break the
//! TOML or the schema; `lambert` must refuse each with exit code 2 and a
//! message naming the line or field, never panic.

use rand::Rng;

/// Probability that a case's file is garbled after generation.
pub const MUTATED_FRACTION: f64 = 0.12;

/// Values that are valid TOML of the wrong type or out of f64's reach.
const WRONG_VALUES: [&str; 14] = [
    "\"1.0\"",
    "true",
    "[]",
    "[1.0, 2.0]",
    "[1.0, 2.0, 3.0, 4.0]",
    "{ x = 1.0 }",
    "1e999",
    "-1e999",
    "123456789012345678901234567890",
    "0x7fffffffffffffff",
    "-nan",
    "+inf",
    "[[1.0, 2.0, 3.0]]",
    "1979-05-27",
];

/// Short byte strings spliced in at random places.
const GARBAGE: [&str; 10] = [
    "[",
    "]",
    "=",
    "\"",
    "#",
    "\n",
    "\u{0}",
    "é",
    "[[emitters]]",
    ",",
];

/// The text after one to three random edits.
pub fn garble<R: Rng>(rng: &mut R, text: &str) -> String {
    let mut text = text.to_owned();
    for _ in 0..rng.random_range(1..=3) {
        text = edit(rng, &text);
    }
    text
}

fn edit<R: Rng>(rng: &mut R, text: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    if lines.is_empty() {
        return "[receiver]\n".to_owned();
    }
    let i = rng.random_range(0..lines.len());
    match rng.random_range(0..11) {
        0 => {
            lines.remove(i);
        }
        1 => {
            let line = lines[i].clone();
            lines.insert(i, line);
        }
        2 => {
            let j = rng.random_range(0..lines.len());
            lines.swap(i, j);
        }
        3 => {
            if let Some((key, _)) = lines[i].split_once(" = ") {
                let value = WRONG_VALUES[rng.random_range(0..WRONG_VALUES.len())];
                lines[i] = format!("{key} = {value}");
            }
        }
        4 => {
            if let Some((key, value)) = lines[i].split_once(" = ") {
                let mut key = key.to_owned();
                if !key.is_empty() {
                    key.remove(rng.random_range(0..key.len()));
                }
                lines[i] = format!("{key} = {value}");
            }
        }
        5 => {
            // Truncated mid-write.
            let cut = floor_char_boundary(text, rng.random_range(0..=text.len()));
            return text[..cut].to_owned();
        }
        6 => {
            let at = floor_char_boundary(text, rng.random_range(0..=text.len()));
            let g = GARBAGE[rng.random_range(0..GARBAGE.len())];
            return format!("{}{g}{}", &text[..at], &text[at..]);
        }
        7 => lines.retain(|l| !l.starts_with('[')),
        8 => lines.insert(0, "title = \"sweep 17\"".to_owned()),
        9 => {
            // A table header of another name, or a receiver given twice.
            let header = ["[receivers]", "[emitter]", "[receiver]", "[[receiver]]"];
            lines.insert(i, header[rng.random_range(0..header.len())].to_owned());
        }
        _ => return String::new(),
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn garbling_keeps_utf8_and_changes_the_text() {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let text = "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n";
        let changed = (0..500).filter(|_| garble(&mut rng, text) != text).count();
        assert!(changed > 400, "{changed}");
    }
}
