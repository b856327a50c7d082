//! Fixed-length number arrays read as exactly that many numbers: serde reads a `[f64; 2]` as
//! the first two elements of a longer array, so `spawn = [1.5, 1.0, 2.0]` ran with the third
//! number dropped and `size = [1.0]` said only "invalid length". Used through
//! `#[serde(deserialize_with = ...)]` on the raw level's fields, so each error keeps the
//! value's line and column.

use std::marker::PhantomData;

use serde::de::{Deserialize, Deserializer, Error, SeqAccess, Visitor};
use toml::Spanned;

/// `N` values of `T`, refused with how many were found when there are more or fewer.
struct Exact<T, const N: usize>([T; N]);

struct ExactVisitor<T, const N: usize>(PhantomData<T>);

impl<'de, T: Deserialize<'de> + Copy + Default, const N: usize> Visitor<'de>
    for ExactVisitor<T, N>
{
    type Value = Exact<T, N>;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "an array of exactly {N} numbers")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut out = [T::default(); N];
        let mut n = 0usize;
        // Every element is read, to say how many there are (the TOML item budget bounds them).
        while let Some(v) = seq.next_element::<T>()? {
            if let Some(slot) = out.get_mut(n) {
                *slot = v;
            }
            n += 1;
        }
        if n != N {
            let s = if n == 1 { "" } else { "s" };
            return Err(A::Error::custom(format!(
                "found an array of {n} number{s}; expected exactly {N}"
            )));
        }
        Ok(Exact(out))
    }
}

impl<'de, T: Deserialize<'de> + Copy + Default, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_seq(ExactVisitor(PhantomData))
    }
}

fn unspan<T, const N: usize>(s: Spanned<Exact<T, N>>) -> Spanned<[T; N]> {
    let span = s.span();
    Spanned::new(span, s.into_inner().0)
}

/// `[T; N]`, exactly `N` elements.
pub(super) fn array<'de, D, T, const N: usize>(d: D) -> Result<[T; N], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Copy + Default,
{
    Exact::<T, N>::deserialize(d).map(|e| e.0)
}

/// `Spanned<[T; N]>`, exactly `N` elements.
pub(super) fn spanned<'de, D, T, const N: usize>(d: D) -> Result<Spanned<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Copy + Default,
{
    Spanned::<Exact<T, N>>::deserialize(d).map(unspan)
}

/// An optional `Spanned<[T; N]>` (with `#[serde(default)]`).
pub(super) fn opt_spanned<'de, D, T, const N: usize>(
    d: D,
) -> Result<Option<Spanned<[T; N]>>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Copy + Default,
{
    Option::<Spanned<Exact<T, N>>>::deserialize(d).map(|o| o.map(unspan))
}

/// A list of `Spanned<[T; N]>`, each exactly `N` elements.
pub(super) fn spanned_list<'de, D, T, const N: usize>(
    d: D,
) -> Result<Vec<Spanned<[T; N]>>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Copy + Default,
{
    Vec::<Spanned<Exact<T, N>>>::deserialize(d).map(|v| v.into_iter().map(unspan).collect())
}

/// An optional list of `[T; N]` (a platform's path), each exactly `N` elements.
pub(super) fn opt_list<'de, D, T, const N: usize>(d: D) -> Result<Option<Vec<[T; N]>>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Copy + Default,
{
    Option::<Vec<Exact<T, N>>>::deserialize(d)
        .map(|o| o.map(|v| v.into_iter().map(|e| e.0).collect()))
}

#[cfg(test)]
mod tests {
    #[derive(serde::Deserialize)]
    struct Raw {
        #[serde(deserialize_with = "super::spanned")]
        at: toml::Spanned<[f64; 2]>,
        #[serde(default, deserialize_with = "super::opt_list")]
        path: Option<Vec<[f64; 2]>>,
    }

    #[test]
    fn exactly_n_numbers_are_read_and_others_refused_at_the_value() {
        let r: Raw = toml::from_str("at = [1.0, 2.0]\npath = [[0.0, 1.0]]").unwrap();
        assert_eq!(*r.at.get_ref(), [1.0, 2.0]);
        assert_eq!(r.at.span(), 5..15);
        assert_eq!(r.path, Some(vec![[0.0, 1.0]]));
        for (text, found) in [
            ("at = [1.0, 2.0, 3.0]", "3 numbers"),
            ("at = [1.0]", "1 number;"),
            ("at = [1.0, 2.0]\npath = [[0.0, 1.0, 2.0]]", "3 numbers"),
        ] {
            let e = toml::from_str::<Raw>(text).err().unwrap().to_string();
            assert!(
                e.contains(&format!("found an array of {found}")),
                "{text}: {e}"
            );
        }
    }
}
