//! Independent references shared by the integration tests.
#![allow(dead_code)]

pub mod bigarc;
pub mod reference;
