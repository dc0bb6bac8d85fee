"""The time domain: the lumped-mass robot stepped in time (explicit velocity Verlet or
implicit Newmark, winding cables, slack segments, an energy ledger), trajectories through
quasi-static cable lengths, and the pendulum on two excited cables (Floquet stability)."""
