//! Curving: real wheel and rail profiles, the contact geometry of a
//! wheelset on the track and its equivalent conicity, and the steady
//! curving of a wheelset or bogie, so that each rail's load, creepages and
//! spin come from the track and the vehicle.

pub mod conicity;
pub mod geometry;
pub mod profile;
pub mod rigid;
pub mod steady;
pub mod table;
pub mod vehicle;
