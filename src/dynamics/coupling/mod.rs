//! The contact coupling between the wheel and the rail: the contact point's
//! closure in every direction (the normal stiffness and the creep forces'
//! response, [`contact_point`]) and the creep forces' small-signal
//! response to a harmonic variation of the creepages, the spin and the
//! normal force ([`creep_response`]).

pub mod contact_point;
pub mod creep_response;
