"""Evidence for the platform-share threshold of the design checks (docs/theory.md §12.1).

For every mode below each scene's band top (CoGiRo at 91 kg and 50 kg, sixcable, fourcable,
planar2), the platform share s = 1 - cable energy fraction and the largest amplification of
a direct platform receptance, max_j |H_jj(f)| / |H_jj(0)| over f within +-0.2 % of the mode,
of the closed-form model with the default damping (dynstiff.Damping()).
"""

import dataclasses

import numpy as np

import dynstiff as ds
from dynstiff.analyses.checks import damped_model


def _with_mass(robot, mass):
    return ds.Robot(robot.anchors, robot.attachments, robot.cables,
                    dataclasses.replace(robot.platform, mass=mass), g=robot.g,
                    tension_limits=robot.tension_limits, name=robot.name)


def run(cases=(("cogiro", None), ("cogiro", 50.0), ("sixcable", None), ("fourcable", None),
               ("planar2", None))):
    """DataFrame: scene, platform mass [kg], freq [Hz], platform share [-],
    amplification [-]."""
    import pandas as pd
    rows = []
    for name, mass in cases:
        sc = ds.load_scene(name)
        rob = sc.robot if mass is None else _with_mass(sc.robot, mass)
        eq = rob.equilibrium(pose=sc.pose) if sc.pose is not None else sc.equilibrium()
        m = damped_model(eq, ds.Damping())
        mo = ds.modes(m.undamped(), fmax_hz=sc.band_hz[1])
        static = np.abs(np.diag(np.linalg.inv(m.dynamic_stiffness(0.0)[0])))
        for f, frac in zip(mo.freq_hz, mo.cable_energy_fraction):
            w = 2 * np.pi * f * (1 + np.linspace(-2e-3, 2e-3, 41))
            H = np.linalg.inv(m.dynamic_stiffness(w))
            amp = np.max(np.abs(np.diagonal(H, axis1=1, axis2=2)) / static)
            rows.append((name, rob.platform.mass, f, 1 - frac, amp))
    return pd.DataFrame(rows, columns=["scene", "platform mass [kg]", "freq [Hz]",
                                       "platform share [-]", "amplification [-]"])


if __name__ == "__main__":
    df = run()
    bins = [0, 0.02, 0.05, 0.1, 0.2, 0.4, 0.5, 1.01]
    import pandas as pd
    df["share bin"] = pd.cut(df["platform share [-]"], bins, right=False)
    print(df.groupby("share bin", observed=True)["amplification [-]"].describe()
          .to_string(float_format=lambda x: f"{x:.3g}"))
