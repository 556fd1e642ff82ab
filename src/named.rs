//! The options' named choices (`"last"`, `"coarse-to-fine"`) read from their names: one reader
//! for every choice, where serde's derived reading compiles a visitor of its own for each enum
//! (about 1.5 KB of the planner's module gzipped apiece). The names are those the enums write
//! with serde (a test of each enum checks them against its derived writing).

/// A choice read by its name: its names and values, in the same order.
pub(crate) trait Named: Sized + Copy + 'static {
    /// The names, as the options spell them.
    const NAMES: &'static [&'static str];
    /// The value of each name.
    const VALUES: &'static [Self];
}

/// Reads a choice from its name; an unknown name is serde's unknown variant error, listing the
/// names.
pub(crate) fn read<'de, D: serde::Deserializer<'de>, T: Named>(d: D) -> Result<T, D::Error> {
    let name = <String as serde::Deserialize>::deserialize(d)?;
    match T::NAMES.iter().position(|n| *n == name) {
        Some(i) => T::VALUES
            .get(i)
            .copied()
            .ok_or_else(|| serde::de::Error::unknown_variant(&name, T::NAMES)),
        None => Err(serde::de::Error::unknown_variant(&name, T::NAMES)),
    }
}

/// Implements [`Named`] and serde's `Deserialize` for a choice: `named!(Type { "name" => Variant,
/// ... })`.
macro_rules! named {
    ($t:ty { $($name:literal => $v:ident),+ $(,)? }) => {
        impl $crate::named::Named for $t {
            const NAMES: &'static [&'static str] = &[$($name),+];
            const VALUES: &'static [Self] = &[$(<$t>::$v),+];
        }
        impl<'de> serde::Deserialize<'de> for $t {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                $crate::named::read(d)
            }
        }
    };
}
pub(crate) use named;

#[cfg(test)]
pub(crate) fn check_names<T: Named + serde::Serialize + PartialEq + std::fmt::Debug>() {
    assert_eq!(T::NAMES.len(), T::VALUES.len());
    for (name, value) in T::NAMES.iter().zip(T::VALUES) {
        assert_eq!(
            serde_json::to_string(value).ok(),
            Some(format!("\"{name}\""))
        );
        let read: T = read(&mut serde_json::Deserializer::from_str(&format!(
            "\"{name}\""
        )))
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(read, *value);
    }
    let e = read::<_, T>(&mut serde_json::Deserializer::from_str("\"nonsense\"")).unwrap_err();
    assert!(
        e.to_string()
            .contains("unknown variant `nonsense`, expected"),
        "{e}"
    );
}

#[cfg(test)]
mod tests {
    use super::check_names;

    #[test]
    fn every_choice_reads_the_names_it_writes() {
        check_names::<crate::headland::HeadlandMode>();
        check_names::<crate::headland::HeadlandOrder>();
        check_names::<crate::headland::HeadlandCorners>();
        check_names::<crate::objective::ObjectiveKind>();
        check_names::<crate::direction::DirectionMode>();
        check_names::<crate::direction::SearchMethod>();
        check_names::<crate::decompose::Decomposition>();
        check_names::<crate::route::pattern::SwathPattern>();
        check_names::<crate::field::Coordinates>();
    }
}
