"""File formats and other tools' data, no physics: CASPR robot models (with their trajectories
and operational spaces) in, FRFs out as UFF 58
records and python-control systems. Optional libraries (pyuff, python-control) are
imported when a file or a system is asked for."""
