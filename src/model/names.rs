//! Names of a model's options as a scene file, the command line and Python write them
//! (`"rigid-body"`, `"small-angle"`, …): one list per option, read by [`std::str::FromStr`] and
//! written by [`std::fmt::Display`], so that every front end parses them the same way.

/// A word that names none of an option's values.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} \"{word}\"; expected one of {}", quoted(.expected))]
pub struct UnknownName {
    /// What the option is ("dynamics", "solver mode", …).
    pub what: &'static str,
    /// The word given.
    pub word: String,
    /// The option's names, in their order.
    pub expected: Vec<&'static str>,
}

fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

/// An enum whose values have names: `ALL` in their order, `as_str`, `Display` and `FromStr`
/// (its error an [`UnknownName`] listing the names).
macro_rules! named {
    ($t:ident, $what:literal, [$($v:ident => $s:literal),+ $(,)?]) => {
        impl $t {
            /// Every value, in the order the documentation lists them.
            pub const ALL: [$t; [$($s),+].len()] = [$($t::$v),+];

            /// The value's name, as a scene file writes it.
            pub fn as_str(self) -> &'static str {
                match self {
                    $($t::$v => $s),+
                }
            }
        }

        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.as_str())
            }
        }

        impl std::str::FromStr for $t {
            type Err = $crate::model::UnknownName;

            fn from_str(word: &str) -> Result<Self, Self::Err> {
                $t::ALL
                    .into_iter()
                    .find(|v| v.as_str() == word)
                    .ok_or_else(|| $crate::model::UnknownName {
                        what: $what,
                        word: word.to_string(),
                        expected: $t::ALL.iter().map(|v| v.as_str()).collect(),
                    })
            }
        }
    };
}

pub(crate) use named;

#[cfg(test)]
mod tests {
    #[derive(Debug, Clone, Copy, PartialEq)]
    enum Colour {
        Red,
        DeepBlue,
    }
    named!(Colour, "colour", [Red => "red", DeepBlue => "deep-blue"]);

    #[test]
    fn a_name_reads_back_as_its_value_and_an_unknown_one_lists_the_names() {
        for c in Colour::ALL {
            assert_eq!(c.to_string().parse::<Colour>(), Ok(c));
        }
        assert_eq!("deep-blue".parse::<Colour>(), Ok(Colour::DeepBlue));
        let e = "blue".parse::<Colour>().unwrap_err();
        assert_eq!(
            e.to_string(),
            "unknown colour \"blue\"; expected one of \"red\", \"deep-blue\""
        );
    }
}
