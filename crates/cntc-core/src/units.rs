//! The unit conventions a caller picks with `cntc_setflags(IF_UNITS)`, and
//! the one conversion between them and the solver's SI units.
//!
//! Everything inside this crate is SI (m, N, Pa, m/s, rad, K, forces on
//! body 1); values cross into it here and leave it here, nowhere else.
//!
//! | convention | length | stress | velocity | spin | temperature | forces on |
//! |---|---|---|---|---|---|---|
//! | CONTACT's (default) | mm | N/mm² | mm/s | rad/mm | °C | body 1 |
//! | SI | m | Pa | m/s | rad/m | K | body 1 |
//! | SIMPACK's | m | Pa | m/s | rad/m | K | body 2 |
//!
//! Forces are in N and angles in rad in all three. Body 1 is the upper
//! body of module 3 and the rail of module 1; under SIMPACK's convention
//! forces, tractions, creepages and slips change sign (they are those on,
//! or of, body 2); displacement differences stay body 1's minus body 2's,
//! as CONTACT's library returns them. Wheel and rail profiles are in
//! mm whatever the convention (CONTACT's rule), unless their own scale
//! factor says otherwise.

use crate::flags;

/// A unit convention.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Units {
    /// CONTACT's: mm, N, N/mm², mm/s, °C; forces on body 1.
    #[default]
    Contact,
    /// SI: m, N, Pa, m/s, K; forces on body 1.
    Si,
    /// SIMPACK's: SI, forces on body 2.
    Simpack,
}

impl Units {
    /// The convention of a `CNTC_un_*` code; `None` for an unknown or
    /// unsupported code.
    pub fn from_code(code: i32) -> Option<Units> {
        match code {
            flags::UN_CNTC => Some(Units::Contact),
            flags::UN_SI => Some(Units::Si),
            flags::UN_SPCK => Some(Units::Simpack),
            _ => None,
        }
    }

    /// Its `CNTC_un_*` code.
    pub fn code(self) -> i32 {
        match self {
            Units::Contact => flags::UN_CNTC,
            Units::Si => flags::UN_SI,
            Units::Simpack => flags::UN_SPCK,
        }
    }

    /// Metres per unit of length.
    pub fn length_m(self) -> f64 {
        match self {
            Units::Contact => 1e-3,
            Units::Si | Units::Simpack => 1.0,
        }
    }

    /// Pascal per unit of stress (force/area).
    pub fn stress_pa(self) -> f64 {
        1.0 / (self.length_m() * self.length_m())
    }

    /// +1 when forces act on body 1, -1 when on body 2 (SIMPACK's).
    pub fn body_sign(self) -> f64 {
        match self {
            Units::Simpack => -1.0,
            Units::Contact | Units::Si => 1.0,
        }
    }

    /// Kelvin of a temperature in this convention.
    pub fn temperature_k(self, t: f64) -> f64 {
        match self {
            Units::Contact => t + 273.15,
            Units::Si | Units::Simpack => t,
        }
    }

    /// A temperature \[K\] in this convention.
    pub fn temperature_from_k(self, t_k: f64) -> f64 {
        match self {
            Units::Contact => t_k - 273.15,
            Units::Si | Units::Simpack => t_k,
        }
    }

    /// SI value of a length.
    pub fn len(self, v: f64) -> f64 {
        v * self.length_m()
    }

    /// A length \[m\] in this convention.
    pub fn len_out(self, v_m: f64) -> f64 {
        v_m / self.length_m()
    }

    /// SI value of a stress.
    pub fn stress(self, v: f64) -> f64 {
        v * self.stress_pa()
    }

    /// A stress \[Pa\] in this convention.
    pub fn stress_out(self, v_pa: f64) -> f64 {
        v_pa / self.stress_pa()
    }

    /// SI value \[m/Pa\] (= m³/N) of a flexibility (volume/force: length
    /// per stress, CONTACT's FLX \[mm³/N\]).
    pub fn flexibility(self, v: f64) -> f64 {
        v * self.length_m() / self.stress_pa()
    }

    /// A flexibility \[m/Pa\] in this convention.
    pub fn flexibility_out(self, v_m_per_pa: f64) -> f64 {
        v_m_per_pa * self.stress_pa() / self.length_m()
    }

    /// SI value of a velocity (length per second).
    pub fn velocity(self, v: f64) -> f64 {
        self.len(v)
    }

    /// A velocity \[m/s\] in this convention.
    pub fn velocity_out(self, v: f64) -> f64 {
        self.len_out(v)
    }

    /// SI value \[1/m\] of a per-length quantity (spin creepage, curvature).
    pub fn per_len(self, v: f64) -> f64 {
        v / self.length_m()
    }

    /// A per-length quantity \[1/m\] in this convention.
    pub fn per_len_out(self, v_per_m: f64) -> f64 {
        v_per_m * self.length_m()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_units_convert_once_each_way() {
        let u = Units::Contact;
        assert_eq!(u.len(2.5), 2.5e-3);
        assert_eq!(u.len_out(u.len(2.5)), 2.5);
        assert_eq!(u.stress(82000.0), 82000.0e6);
        assert_eq!(u.per_len(1e-3), 1.0);
        assert!((u.temperature_k(20.0) - 293.15).abs() < 1e-12);
        assert_eq!(Units::Simpack.body_sign(), -1.0);
        assert_eq!(Units::from_code(flags::UN_IMPER), None);
        for u in [Units::Contact, Units::Si, Units::Simpack] {
            assert_eq!(Units::from_code(u.code()), Some(u));
        }
    }
}
