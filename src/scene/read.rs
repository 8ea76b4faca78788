//! From TOML text to a [`Scene`]: parse once, keep the document, and give every error the line
//! and column of the key it names (or of the nearest enclosing key the file has).

use super::error::SceneErrorKind;
use super::files::{Files, Sources};
use super::raw::{self, ReadError};
use super::validate::validate;
use super::{Scene, SceneError};
use std::path::Path;
use toml::de::{DeTable, DeValue};

/// Parses and validates scene text; `origin` names the source in errors.
pub(super) fn from_toml(text: &str, origin: &str, folder: &Path) -> Result<Scene, SceneError> {
    let doc = DeTable::parse(text).map_err(|e| {
        let mut err = SceneError::of(
            SceneErrorKind::Unreadable,
            origin,
            "",
            format!("not valid TOML: {}", e.message()),
        );
        err.position = e.span().map(|s| line_col(text, s.start));
        err
    })?;
    let located = |mut e: SceneError| {
        if e.position.is_none() {
            e.position = key_span(doc.get_ref(), &e.key).map(|at| line_col(text, at));
        }
        e
    };
    if let Some((key, at, digits)) = too_large_integer(doc.get_ref(), "") {
        let mut err = SceneError::of(
            SceneErrorKind::WrongType,
            origin,
            key,
            format!(
                "a whole number of {digits} digits, beyond the 64-bit integers a scene may hold \
                 (about ±9.2e18); a number with a point or an exponent (1.0e19) is read as a \
                 decimal"
            ),
        );
        err.position = Some(line_col(text, at));
        return Err(err);
    }
    let table =
        <toml::Table as serde::Deserialize>::deserialize(toml::Deserializer::from(doc.clone()))
            .map_err(|e| {
                SceneError::of(
                    SceneErrorKind::Unreadable,
                    origin,
                    "",
                    format!("not a table of keys: {}", e.message()),
                )
            })?;
    let files = Files::default();
    let sources = Sources {
        folder,
        files: &files,
    };
    let located_all = |e: SceneError| {
        let also = e.also.iter().cloned().map(located).collect();
        SceneError { also, ..located(e) }
    };
    let raw = raw::read(toml::Deserializer::from(doc.clone()))
        .map_err(|e| located_all(read_error(e, origin, Some(text), &table, &sources)))?;
    validate(raw, origin, table, sources).map_err(located_all)
}

/// A document given as a table (a scene edited by key, [`Scene::with`]): errors name the key,
/// without a position.
/// `sources` has the files the scene named when it was read: one it still names is not read
/// again.
pub(super) fn from_table(
    table: toml::Table,
    origin: &str,
    sources: Sources,
) -> Result<Scene, SceneError> {
    let raw = raw::read(toml::Value::Table(table.clone()))
        .map_err(|e| read_error(e, origin, None, &table, &sources))?;
    validate(raw, origin, table, sources)
}

/// The first whole number in `table` (whose keys are under `prefix`) that no 64-bit integer
/// holds — TOML allows none, and a [`toml::Value`] cannot hold one — as the key errors name
/// (`section.key`, a list of tables' item `name[k].key`), the offset where it is written and
/// how many digits it has.
fn too_large_integer(table: &DeTable<'_>, prefix: &str) -> Option<(String, usize, usize)> {
    table.iter().find_map(|(name, value)| {
        let name: &str = name.get_ref().as_ref();
        let key = if prefix.is_empty() {
            name.to_string()
        } else {
            format!("{prefix}.{name}")
        };
        too_large_in(value, &key)
    })
}

/// [`too_large_integer`] in one value, `key` its key.
fn too_large_in(value: &toml::Spanned<DeValue<'_>>, key: &str) -> Option<(String, usize, usize)> {
    match value.get_ref() {
        DeValue::Integer(i) if i64::from_str_radix(i.as_str(), i.radix()).is_err() => {
            let digits = i
                .as_str()
                .chars()
                .filter(char::is_ascii_alphanumeric)
                .count();
            Some((key.to_string(), value.span().start, digits))
        }
        DeValue::Table(t) => too_large_integer(t, key),
        DeValue::Array(items) => items
            .iter()
            .enumerate()
            .find_map(|(k, v)| match v.get_ref() {
                DeValue::Table(t) => too_large_integer(t, &format!("{key}[{k}]")),
                _ => too_large_in(v, key),
            }),
        _ => None,
    }
}

/// The error of a document that is not a scene's: every unknown key, and the faults of the
/// scene read without them (`table`, from `sources`).
fn read_error(
    e: ReadError,
    origin: &str,
    text: Option<&str>,
    table: &toml::Table,
    sources: &Sources,
) -> SceneError {
    match e {
        ReadError::Unknown { keys, raw } => {
            let mut errors = keys.iter().map(|key| unknown_key(key, origin));
            let Some(first) = errors.next() else {
                return SceneError::of(SceneErrorKind::UnknownKey, origin, "", "unknown key");
            };
            let rest = validate(*raw, origin, table.clone(), *sources).err();
            first.with_also(errors.chain(rest))
        }
        ReadError::WrongType { key, message, span } => {
            let mut err = SceneError::of(SceneErrorKind::WrongType, origin, key, message);
            if let (Some(text), Some(span)) = (text, span) {
                err.position = Some(line_col(text, span.start));
            }
            err
        }
    }
}

/// The fault of a key no scene has, listing the keys its section has.
fn unknown_key(key: &str, origin: &str) -> SceneError {
    let (section, name) = key.rsplit_once('.').unwrap_or(("", key));
    let known = raw::keys_of(section).join(", ");
    let reason = if section.is_empty() {
        format!("unknown key `{name}`; a scene's sections are {known}")
    } else if known.is_empty() {
        format!("unknown key `{name}`; [{section}] is not a section of keys")
    } else {
        format!("unknown key `{name}`; the keys of [{section}] are {known}")
    };
    SceneError::of(SceneErrorKind::UnknownKey, origin, key, reason)
}

/// Where `key` (`section.key`, dotted) is written: its name's offset, or its section's when the
/// file lacks the key itself.
fn key_span(root: &DeTable<'_>, key: &str) -> Option<usize> {
    let mut table = root;
    let mut found = None;
    for part in key.split('.').filter(|p| !p.is_empty()) {
        // A list item is written `name[k]`.
        let (part, item) = match part.split_once('[') {
            Some((name, rest)) => (name, rest.trim_end_matches(']').parse::<usize>().ok()),
            None => (part, None),
        };
        let Some((name, value)) = table.iter().find(|(k, _)| k.get_ref().as_ref() == part) else {
            break;
        };
        found = Some(name.span().start);
        let value = match (value.get_ref(), item) {
            (DeValue::Array(items), Some(k)) => match items.get(k) {
                Some(v) => {
                    found = Some(v.span().start);
                    v.get_ref()
                }
                None => break,
            },
            (v, _) => v,
        };
        match value {
            DeValue::Table(t) => table = t,
            _ => break,
        }
    }
    found
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut end = offset.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}
