// Nothing more after a particle's conduction.

fn conduction_done(i: u32) {}
