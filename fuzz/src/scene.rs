//! A scene file as a tree of named values, written as TOML in the format
//! `lambert` reads (`[receiver]` and `[[emitters]]` tables), and read back
//! from any TOML text so that the shrinker can simplify it field by field.
//!
//! The tree holds whatever a file can hold, valid or not: a field may be
//! missing, repeated across kinds, of the wrong type or non-finite. Floats
//! are written so that they parse back to the same bits
//! ([`crate::numbers::toml_float`]).

use crate::numbers::toml_float;

/// One value of a scene file.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A number (written as a TOML float).
    Float(f64),
    /// A 3-vector `[x, y, z]`.
    Vector([f64; 3]),
    /// A list of 3-vectors (polygon vertices).
    Vectors(Vec<[f64; 3]>),
    /// A boolean.
    Bool(bool),
    /// A string.
    Text(String),
    /// Any other TOML value, written as TOML writes it (wrong types, arrays
    /// of the wrong length, tables).
    Other(toml::Value),
}

impl Value {
    /// The TOML spelling of the value.
    pub fn to_toml(&self) -> String {
        match self {
            Value::Float(x) => toml_float(*x),
            Value::Vector(v) => vector(v),
            Value::Vectors(vs) => {
                let items: Vec<String> = vs.iter().map(vector).collect();
                format!("[{}]", items.join(", "))
            }
            Value::Bool(b) => b.to_string(),
            Value::Text(s) => toml::Value::String(s.clone()).to_string(),
            Value::Other(v) => v.to_string(),
        }
    }

    fn from_toml(v: &toml::Value) -> Value {
        let number = |v: &toml::Value| match v {
            toml::Value::Float(x) => Some(*x),
            toml::Value::Integer(i) => Some(*i as f64),
            _ => None,
        };
        let triple = |v: &toml::Value| -> Option<[f64; 3]> {
            let a = v.as_array()?;
            if a.len() != 3 {
                return None;
            }
            Some([number(&a[0])?, number(&a[1])?, number(&a[2])?])
        };
        match v {
            // Integers stay as written: `1` and `1.0` are both valid, but
            // a shrunk file should not change what the parser saw.
            toml::Value::Float(x) => Value::Float(*x),
            toml::Value::Boolean(b) => Value::Bool(*b),
            toml::Value::String(s) => Value::Text(s.clone()),
            toml::Value::Array(a) => {
                let floats_only = |v: &toml::Value| {
                    v.as_array()
                        .is_some_and(|a| a.iter().all(|x| matches!(x, toml::Value::Float(_))))
                };
                if floats_only(v) {
                    if let Some(t) = triple(v) {
                        return Value::Vector(t);
                    }
                }
                if !a.is_empty() && a.iter().all(floats_only) {
                    if let Some(ts) = a.iter().map(triple).collect::<Option<Vec<_>>>() {
                        return Value::Vectors(ts);
                    }
                }
                Value::Other(v.clone())
            }
            other => Value::Other(other.clone()),
        }
    }
}

fn vector(v: &[f64; 3]) -> String {
    format!(
        "[{}, {}, {}]",
        toml_float(v[0]),
        toml_float(v[1]),
        toml_float(v[2])
    )
}

/// The order in which fields are written back after reading.
const KEY_ORDER: [&str; 16] = [
    "kind",
    "point",
    "center",
    "position",
    "normal",
    "direction",
    "axis",
    "vertices",
    "radius",
    "half_angle",
    "half_angle_deg",
    "radiance",
    "intensity",
    "flux",
    "irradiance",
    "two_sided",
];

/// The fields of one table, in the order they are written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// `(key, value)` pairs.
    pub fields: Vec<(String, Value)>,
}

impl Table {
    /// Appends a field.
    pub fn set(&mut self, key: &str, value: Value) {
        self.fields.push((key.to_owned(), value));
    }

    /// Sets `key` to `value`: in place if present, appended otherwise.
    pub fn put(&mut self, key: &str, value: Value) {
        match self.fields.iter_mut().find(|(k, _)| k == key) {
            Some((_, v)) => *v = value,
            None => self.set(key, value),
        }
    }

    /// The value of `key`, if present.
    pub fn get(&self, key: &str) -> Option<&Value> {
        self.fields.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }

    /// The number at `key`, if it is one.
    pub fn float(&self, key: &str) -> Option<f64> {
        match self.get(key)? {
            Value::Float(x) => Some(*x),
            _ => None,
        }
    }

    /// The vector at `key`, if it is one.
    pub fn vector(&self, key: &str) -> Option<[f64; 3]> {
        match self.get(key)? {
            Value::Vector(v) => Some(*v),
            _ => None,
        }
    }

    /// The string at `key`, if it is one.
    pub fn text(&self, key: &str) -> Option<&str> {
        match self.get(key)? {
            Value::Text(s) => Some(s),
            _ => None,
        }
    }

    /// Removes `key` (every occurrence).
    pub fn remove(&mut self, key: &str) {
        self.fields.retain(|(k, _)| k != key);
    }

    fn write(&self, out: &mut String) {
        for (k, v) in &self.fields {
            out.push_str(&format!("{k} = {}\n", v.to_toml()));
        }
    }

    fn from_toml(t: &toml::Table) -> Table {
        let mut fields: Vec<(String, Value)> = t
            .iter()
            .map(|(k, v)| (k.clone(), Value::from_toml(v)))
            .collect();
        // The TOML reader sorts keys; put them back in the order a person
        // writes them (`kind` first), unknown keys last.
        fields.sort_by_key(|(k, _)| {
            KEY_ORDER
                .iter()
                .position(|o| o == k)
                .unwrap_or(KEY_ORDER.len())
        });
        Table { fields }
    }
}

/// A whole scene file: top-level extras (unknown keys, which `lambert`
/// must refuse), an optional receiver table and the emitters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneFile {
    /// Top-level key/value pairs other than the two tables.
    pub extra: Vec<(String, Value)>,
    /// The `[receiver]` table, if present.
    pub receiver: Option<Table>,
    /// The `[[emitters]]` tables.
    pub emitters: Vec<Table>,
}

impl SceneFile {
    /// The file's text.
    pub fn to_toml(&self) -> String {
        let mut out = String::new();
        for (k, v) in &self.extra {
            out.push_str(&format!("{k} = {}\n", v.to_toml()));
        }
        if let Some(r) = &self.receiver {
            if !out.is_empty() {
                out.push('\n');
            }
            out.push_str("[receiver]\n");
            r.write(&mut out);
        }
        for e in &self.emitters {
            out.push_str("\n[[emitters]]\n");
            e.write(&mut out);
        }
        out
    }

    /// Reads any TOML text whose `receiver` is a table and whose `emitters`
    /// (if present) is an array of tables; `None` otherwise (syntax errors
    /// included).
    pub fn from_toml(text: &str) -> Option<SceneFile> {
        let table: toml::Table = text.parse().ok()?;
        let mut file = SceneFile::default();
        for (k, v) in &table {
            match (k.as_str(), v) {
                ("receiver", toml::Value::Table(t)) => file.receiver = Some(Table::from_toml(t)),
                ("emitters", toml::Value::Array(a)) => {
                    for e in a {
                        file.emitters.push(Table::from_toml(e.as_table()?));
                    }
                }
                ("receiver" | "emitters", _) => return None,
                (_, toml::Value::Table(_)) => return None,
                _ => file.extra.push((k.clone(), Value::from_toml(v))),
            }
        }
        Some(file)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_and_reads_back_the_same_tree() {
        let mut receiver = Table::default();
        receiver.set("point", Value::Vector([0.0, -0.0, 1e-300]));
        receiver.set("normal", Value::Vector([f64::NAN, 1.0, f64::INFINITY]));
        let mut disk = Table::default();
        disk.set("kind", Value::Text("disk".into()));
        disk.set("radius", Value::Float(5e-324));
        disk.set("two_sided", Value::Bool(true));
        let mut polygon = Table::default();
        polygon.set(
            "vertices",
            Value::Vectors(vec![[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1e308]]),
        );
        polygon.set("colour", Value::Other(toml::Value::Integer(3)));
        let file = SceneFile {
            extra: vec![("title".into(), Value::Text("x".into()))],
            receiver: Some(receiver),
            emitters: vec![disk, polygon],
        };
        let text = file.to_toml();
        let back = SceneFile::from_toml(&text).expect("parses");
        // NaN != NaN: compare the texts.
        assert_eq!(back.to_toml(), text);
    }
}
