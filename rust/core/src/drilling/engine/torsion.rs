//! The torsional field of a run as a [`StringField`]: the [`Field`] of `(omega, tau)` with the
//! torsional wall friction per cell ([`WallFriction`]) and the sources' constants
//! ([`Sources`]), advanced by the transport kernel ([`super::kernel`]; the published scheme
//! [`super::kernel_published`] with `numerics.source_speed = "before_transport"`, the Godunov
//! update with `nonlinearity = "consistent"`). Its ends (the top drive, the bit) are the run's
//! ([`super::run::Simulation`]), its channels [`TORSIONAL`].

use super::energy::Ledger;
use super::field::{Field, StringField};
use super::kernel::{godunov, transport, transport_unbooked};
use super::kernel_published::transport as before_transport;
use super::sampler::{Channel, TORSIONAL};
use super::sources::{Sources, WallFriction};
use crate::drilling::config::SourceSpeed;

/// The torsional field, its wall friction and sources.
#[derive(Clone)]
pub struct Torsion {
    pub field: Field,
    /// The wall friction per cell (zero limits when a coupled run's friction applies it,
    /// [`super::sources::StepSource`]).
    pub wall: WallFriction,
    pub sources: Sources,
    /// Where the sources take the speed (`numerics.source_speed`).
    pub source_speed: SourceSpeed,
}

impl StringField for Torsion {
    #[inline]
    fn channels() -> &'static [Channel] {
        &TORSIONAL
    }

    #[inline]
    fn field(&self) -> &Field {
        &self.field
    }

    #[inline]
    fn field_mut(&mut self) -> &mut Field {
        &mut self.field
    }

    /// The cells of every section over a step, the sources' and transport's work booked (the
    /// `consistent` scheme's always; without the ledger the linear transport runs without the
    /// energy terms, the published scheme's are computed and not booked).
    fn advance(&mut self, dt: f64, ledger: &mut Ledger, booked: bool) {
        let Field { sections, alpha, beta, alpha_next, beta_next, nl } = &mut self.field;
        let (stop, slip) = self.wall.limits();
        if let Some(nl) = nl {
            for (s, sp) in sections.iter().enumerate() {
                let law = nl.laws[s];
                let sums = godunov(nl, sp, law, (stop, slip), dt, &self.sources);
                ledger.godunov(&sums);
                nl.peak_strain[s] = nl.peak_strain[s].max(sums.peak);
            }
        } else {
            let published = self.source_speed == SourceSpeed::BeforeTransport;
            for sp in sections.iter() {
                let r = sp.padded();
                let (a, b, wall) = (&alpha[r.clone()], &beta[r.clone()], self.wall.wall(r.clone()));
                let (an, bn) = (&mut alpha_next[r.clone()], &mut beta_next[r.clone()]);
                if !published && !booked {
                    transport_unbooked(a, b, wall, an, bn, sp.courant, &self.sources);
                    continue;
                }
                let sums = if published {
                    before_transport(a, b, &stop[r.clone()], &slip[r], an, bn, sp.courant, &self.sources)
                } else {
                    transport(a, b, wall, an, bn, sp.courant, &self.sources)
                };
                if booked {
                    ledger.transport(sp.e, sp.courant, &sums);
                }
            }
        }
        self.field.swap();
    }

    #[inline]
    fn each_cell(&self, f: impl FnMut(f64, f64)) {
        self.field.each_cell(f);
    }
}
