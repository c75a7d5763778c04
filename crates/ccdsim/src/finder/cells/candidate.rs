//! A scan's candidates: the body being predicted ([`Probe`]) and the two earliest events
//! found for it so far ([`Best`]).

use super::key::Key;
use crate::motion::Body;
use crate::world::World;

/// The two earliest of one body's candidate events.
///
/// `second` is a lower bound of every candidate but `key`'s own, as long as `known`; when the
/// cached `key` goes stale, `second` can take its place without a rescan (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(super) struct Best {
    /// The earliest candidate so far under the full event order.
    pub key: Key,
    /// For a body–body candidate: the image code of the partner (see `Grid::visit_product`).
    pub image: u8,
    /// The second earliest candidate (or a lower bound of all but `key`'s).
    pub second: Key,
    /// Image code of `second`'s partner.
    pub second_image: u8,
    /// `second` is valid; false after `second` was promoted, until the next full scan.
    pub known: bool,
}

impl Best {
    /// No candidate yet.
    pub const NONE: Best = Best {
        key: Key::NEVER,
        image: 0,
        second: Key::NEVER,
        second_image: 0,
        known: true,
    };

    /// Time word below which a candidate changes the records.
    #[inline(always)]
    pub fn threshold(&self) -> u64 {
        if self.known {
            self.second.time
        } else {
            self.key.time
        }
    }

    /// Takes a candidate into account.
    #[inline]
    pub fn offer(&mut self, key: Key, image: u8) {
        if key < self.key {
            // The old earliest bounds everything else from below, the new candidate excepted.
            self.second = self.key;
            self.second_image = self.image;
            self.known = true;
            self.key = key;
            self.image = image;
        } else if self.known && key < self.second {
            self.second = key;
            self.second_image = image;
        }
    }
}

/// A body whose events are being predicted: its index and a copy of its hot record.
#[derive(Clone, Copy, Debug)]
pub(super) struct Probe<const D: usize> {
    /// Body index.
    pub i: usize,
    /// Its stored motion and radius.
    pub b: Body<D>,
}

impl<const D: usize> Probe<D> {
    /// Body `i` of `world`.
    #[inline]
    pub fn of(world: &World<D>, i: usize) -> Self {
        Probe {
            i,
            b: world.bodies()[i],
        }
    }
}
