#![allow(dead_code)]

pub mod bigarc;
