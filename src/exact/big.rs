//! Signed integers of up to 768 bits for the exact predicates' fallbacks
//! ([`super::predicates`]): a product costs the limbs its operands have. A cut line's
//! coefficients have four or five 64-bit limbs and an edge's one or two, where a fixed-width
//! 768-bit integer multiplies twelve by twelve whatever the values (most of a fallback's time
//! on meshes with many: samurai_monastery's are mostly three cut lines).
//!
//! Invariant: `limbs[..len]` is the magnitude, least significant limb first, with no zero limb
//! on top and nothing but zeros above `len`; zero is `len == 0` and never negative. Values stay
//! below 2^768 in magnitude: the callers' determinants are bounded below 2^717 (the
//! `predicates` module docs), and every operation checks that its result fits.

use bnum::cast::As;
use bnum::types::{I256, U256};
use std::cmp::Ordering;
use std::ops::{Add, Mul, Neg, Sub};

/// Limbs of 64 bits: 768 bits in all.
const LIMBS: usize = 12;

/// A signed integer below 2^768 in magnitude. See the module docs.
#[derive(Clone, Copy, Debug)]
pub struct Big {
    negative: bool,
    len: u8,
    limbs: [u64; LIMBS],
}

impl Big {
    /// Zero.
    pub const ZERO: Big = Big {
        negative: false,
        len: 0,
        limbs: [0; LIMBS],
    };

    /// `v` exactly.
    pub fn from_i128(v: i128) -> Big {
        let m = v.unsigned_abs();
        let mut b = Big {
            negative: v < 0,
            len: 2,
            limbs: [0; LIMBS],
        };
        b.limbs[0] = m as u64;
        b.limbs[1] = (m >> 64) as u64;
        b.trimmed()
    }

    /// `v` exactly.
    pub fn from_i256(v: I256) -> Big {
        let m: U256 = v.unsigned_abs();
        let mut b = Big {
            negative: v.is_negative(),
            len: 4,
            limbs: [0; LIMBS],
        };
        for (k, limb) in b.limbs[..4].iter_mut().enumerate() {
            *limb = (m >> (64 * k as u32)).as_::<u64>();
        }
        b.trimmed()
    }

    /// The sign: `Less`, `Equal` (zero) or `Greater`.
    pub fn signum(&self) -> Ordering {
        match (self.len, self.negative) {
            (0, _) => Ordering::Equal,
            (_, true) => Ordering::Less,
            (_, false) => Ordering::Greater,
        }
    }

    /// Drops zero limbs from the top; zero is not negative.
    fn trimmed(mut self) -> Big {
        while self.len > 0 && self.limbs[self.len as usize - 1] == 0 {
            self.len -= 1;
        }
        if self.len == 0 {
            self.negative = false;
        }
        self
    }

    /// The value as a fixed-width integer of `W` bytes, which must hold it (for division).
    pub fn to_bnum<const W: usize>(self) -> bnum::Int<W> {
        let mut v: bnum::Int<W> = 0i32.as_();
        for (k, &limb) in self.magnitude().iter().enumerate() {
            v += limb.as_::<bnum::Int<W>>() << (64 * k as u32);
        }
        if self.negative { -v } else { v }
    }

    fn magnitude(&self) -> &[u64] {
        &self.limbs[..self.len as usize]
    }

    /// Compares magnitudes.
    fn cmp_magnitude(&self, o: &Big) -> Ordering {
        self.len.cmp(&o.len).then_with(|| {
            self.magnitude()
                .iter()
                .rev()
                .cmp(o.magnitude().iter().rev())
        })
    }

    /// `|a| + |b|` with the sign `negative`.
    fn sum_of_magnitudes(a: &Big, b: &Big, negative: bool) -> Big {
        let (long, short) = if a.len >= b.len { (a, b) } else { (b, a) };
        let mut out = Big {
            negative,
            len: long.len,
            limbs: [0; LIMBS],
        };
        let mut carry = false;
        for k in 0..long.len as usize {
            let (s, c1) = long.limbs[k].overflowing_add(short.limbs[k]);
            let (s, c2) = s.overflowing_add(carry as u64);
            out.limbs[k] = s;
            carry = c1 || c2;
        }
        if carry {
            let top = long.len as usize;
            assert!(top < LIMBS, "exact integer beyond 768 bits");
            out.limbs[top] = 1;
            out.len += 1;
        }
        out
    }

    /// `|a| - |b|` for `|a| >= |b|`, with the sign `negative`.
    fn difference_of_magnitudes(a: &Big, b: &Big, negative: bool) -> Big {
        let mut out = Big {
            negative,
            len: a.len,
            limbs: [0; LIMBS],
        };
        let mut borrow = false;
        for k in 0..a.len as usize {
            let (d, b1) = a.limbs[k].overflowing_sub(b.limbs[k]);
            let (d, b2) = d.overflowing_sub(borrow as u64);
            out.limbs[k] = d;
            borrow = b1 || b2;
        }
        debug_assert!(!borrow, "the larger magnitude first");
        out.trimmed()
    }
}

impl Neg for Big {
    type Output = Big;
    fn neg(mut self) -> Big {
        self.negative = self.len > 0 && !self.negative;
        self
    }
}

impl Add for Big {
    type Output = Big;
    fn add(self, o: Big) -> Big {
        if self.negative == o.negative {
            return Big::sum_of_magnitudes(&self, &o, self.negative);
        }
        match self.cmp_magnitude(&o) {
            Ordering::Less => Big::difference_of_magnitudes(&o, &self, o.negative),
            _ => Big::difference_of_magnitudes(&self, &o, self.negative),
        }
    }
}

impl Sub for Big {
    type Output = Big;
    fn sub(self, o: Big) -> Big {
        self + -o
    }
}

impl Mul for Big {
    type Output = Big;
    /// Schoolbook over the limbs the operands have.
    fn mul(self, o: Big) -> Big {
        let (a, b) = (self.magnitude(), o.magnitude());
        if a.is_empty() || b.is_empty() {
            return Big::ZERO;
        }
        // A product of n and m limbs has n + m - 1 or n + m of them.
        assert!(
            a.len() + b.len() - 1 <= LIMBS,
            "exact integer beyond 768 bits"
        );
        let mut wide = [0u64; LIMBS + 1];
        for (i, &x) in a.iter().enumerate() {
            let mut carry = 0u64;
            for (j, &y) in b.iter().enumerate() {
                // x·y + wide + carry < 2^128: (2^64 - 1)^2 + 2·(2^64 - 1) = 2^128 - 1.
                let t = x as u128 * y as u128 + wide[i + j] as u128 + carry as u128;
                wide[i + j] = t as u64;
                carry = (t >> 64) as u64;
            }
            wide[i + b.len()] = carry;
        }
        assert!(wide[LIMBS] == 0, "exact integer beyond 768 bits");
        let mut limbs = [0u64; LIMBS];
        limbs.copy_from_slice(&wide[..LIMBS]);
        Big {
            negative: self.negative != o.negative,
            len: (a.len() + b.len()).min(LIMBS) as u8,
            limbs,
        }
        .trimmed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bnum::types::I1024;
    use proptest::prelude::*;

    /// The value in 1024 bits, for comparison.
    fn wide(b: &Big) -> I1024 {
        b.to_bnum::<128>()
    }

    fn int(v: i128) -> I1024 {
        v.as_()
    }

    /// A value of `bits` bits at most from random limbs, with its sign.
    fn value(limbs: [u64; 6], bits: u32, negative: bool) -> (Big, I1024) {
        let mut v = int(0);
        for (k, &limb) in limbs.iter().enumerate() {
            v += limb.as_::<I1024>() << (64 * k as u32);
        }
        v &= (int(1) << bits) - int(1);
        let v = if negative { -v } else { v };
        let mut b = Big::ZERO;
        let m = v.unsigned_abs();
        for k in 0..6 {
            b.limbs[k] = (m >> (64 * k as u32)).as_::<u64>();
        }
        b.len = 6;
        b.negative = negative;
        (b.trimmed(), v)
    }

    fn bits() -> impl Strategy<Value = u32> {
        // Values near limb boundaries and all the way up to 384 bits (products to 768).
        prop_oneof![
            0u32..=384,
            Just(63),
            Just(64),
            Just(65),
            Just(128),
            Just(383),
            Just(384)
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]

        /// Sums, differences and products agree with 1024-bit integers, and signs with theirs.
        #[test]
        fn arithmetic_agrees_with_wide_integers(
            la in any::<[u64; 6]>(), lb in any::<[u64; 6]>(),
            ba in bits(), bb in bits(), na: bool, nb: bool,
        ) {
            let ((a, wa), (b, wb)) = (value(la, ba, na), value(lb, bb, nb));
            prop_assert_eq!(wide(&a), wa);
            prop_assert_eq!(wide(&(a + b)), wa + wb);
            prop_assert_eq!(wide(&(a - b)), wa - wb);
            prop_assert_eq!(wide(&(b - a)), wb - wa);
            prop_assert_eq!(wide(&(a - a)), int(0));
            prop_assert_eq!(wide(&(a * b)), wa * wb);
            prop_assert_eq!(wide(&-a), -wa);
            prop_assert_eq!((a * b).signum(), (wa * wb).cmp(&int(0)));
            prop_assert_eq!((a - b).signum(), wa.cmp(&wb));
        }
    }

    #[test]
    fn conversions_are_exact_at_the_extremes() {
        for v in [
            0,
            1,
            -1,
            i128::MAX,
            i128::MIN,
            i128::MIN + 1,
            1 << 64,
            -(1 << 64),
        ] {
            assert_eq!(wide(&Big::from_i128(v)), int(v), "{v}");
        }
        let one: I256 = 1i32.as_();
        for v in [I256::MAX, I256::MIN, I256::MIN + one, 0i32.as_(), -one] {
            assert_eq!(wide(&Big::from_i256(v)), v.as_::<I1024>(), "{v}");
        }
        assert_eq!(Big::from_i128(0).signum(), Ordering::Equal);
        assert_eq!((-Big::ZERO).signum(), Ordering::Equal);
    }

    /// The largest products the predicates take (2^716) fit; one past 768 bits is refused.
    #[test]
    fn products_up_to_768_bits_fit_and_beyond_panic() {
        let two_to = |k: u32| {
            let mut b = Big::ZERO;
            b.limbs[(k / 64) as usize] = 1 << (k % 64);
            b.len = (k / 64 + 1) as u8;
            b
        };
        assert_eq!(wide(&(two_to(383) * two_to(384))), int(1) << 767);
        let too_big = std::panic::catch_unwind(|| two_to(384) * two_to(384));
        assert!(too_big.is_err());
    }
}
