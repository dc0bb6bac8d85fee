"""The main job and its documents: the robot's report (``dynstiff demo``/``report``: tables,
figures and a self-contained HTML page), the single-cable report, and the 3-D views of the
robot and its mode shapes with the cables' own displacement fields."""
