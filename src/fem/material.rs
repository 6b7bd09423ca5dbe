//! Isotropic linear elasticity (small strain) and its finite-strain extension,
//! St Venant–Kirchhoff (the same law applied to Green–Lagrange strain, giving the second
//! Piola–Kirchhoff stress).
//!
//! Voigt order everywhere: [xx, yy, zz, xy] with engineering shear strain γ = 2ε_xy.
//! In axisymmetry x is the radius r, y the axis z, and "zz" the hoop component θθ.

use crate::error::{Error, Result};

#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Modelisation {
    PlaneStrain,
    PlaneStress,
    Axisymmetric,
}

impl Modelisation {
    pub fn name(self) -> &'static str {
        match self {
            Modelisation::PlaneStrain => "plane_strain",
            Modelisation::PlaneStress => "plane_stress",
            Modelisation::Axisymmetric => "axisymmetric",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastic {
    pub young: f64,
    pub poisson: f64,
}

impl Elastic {
    /// Checks the parameters; `what` names the material for the error message.
    pub fn new(young: f64, poisson: f64, what: &str) -> Result<Self> {
        if !(young > 0.0 && young.is_finite()) {
            return Err(Error::model(format!(
                "{what}: Young's modulus E must be positive, got {young}"
            )));
        }
        if !(poisson > -1.0 && poisson < 0.5) {
            return Err(Error::model(format!(
                "{what}: Poisson's ratio nu must lie in (-1, 0.5), got {poisson}"
            )));
        }
        Ok(Elastic { young, poisson })
    }

    /// Lamé constants (λ, μ).
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.young, self.poisson);
        (
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            e / (2.0 * (1.0 + nu)),
        )
    }

    /// Elasticity matrix on [xx, yy, zz, xy] (engineering shear). In plane stress the zz
    /// row and column are zero (σ_zz = 0 and ε_zz is eliminated).
    pub fn matrix(&self, model: Modelisation) -> [[f64; 4]; 4] {
        let (l, m) = self.lame();
        match model {
            Modelisation::PlaneStress => {
                let c = self.young / (1.0 - self.poisson * self.poisson);
                let nu = self.poisson;
                [
                    [c, c * nu, 0.0, 0.0],
                    [c * nu, c, 0.0, 0.0],
                    [0.0; 4],
                    [0.0, 0.0, 0.0, m],
                ]
            }
            _ => [
                [l + 2.0 * m, l, l, 0.0],
                [l, l + 2.0 * m, l, 0.0],
                [l, l, l + 2.0 * m, 0.0],
                [0.0, 0.0, 0.0, m],
            ],
        }
    }

    /// Out-of-plane strain in plane stress (σ_zz = 0), from the in-plane strains.
    pub fn plane_stress_ezz(&self, exx: f64, eyy: f64) -> f64 {
        -self.poisson / (1.0 - self.poisson) * (exx + eyy)
    }
}

/// σ = D ε on the 4-component Voigt vectors.
pub fn apply(d: &[[f64; 4]; 4], e: &[f64; 4]) -> [f64; 4] {
    let mut s = [0.0; 4];
    for i in 0..4 {
        for j in 0..4 {
            s[i] += d[i][j] * e[j];
        }
    }
    s
}

/// Von Mises equivalent stress of [xx, yy, zz, xy].
pub fn von_mises(s: &[f64; 4]) -> f64 {
    let (a, b, c, t) = (s[0], s[1], s[2], s[3]);
    (0.5 * ((a - b).powi(2) + (b - c).powi(2) + (c - a).powi(2)) + 3.0 * t * t).sqrt()
}
