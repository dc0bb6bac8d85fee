"""
The built-in robots
===================

The scenes shipped with dynstiff, each at the pose of its scene file: CoGiRo and the
robots of the seed papers (a planar two-cable point mass, a six-cable spatial robot, a
four-cable suspended point mass, an inverted pendulum on two cables, an eight-cable motion
simulator). ``dynstiff.load_scene(name)`` returns any of them.
"""

import matplotlib.pyplot as plt

import dynstiff as ds
from dynstiff.report.robot3d import plot_robot

names = ds.list_scenes()
for name in names:
    print(f"{name:<10s} {ds.load_scene(name).description}")

# %%
# Each robot at the equilibrium of its scene (anchors as squares, the platform in orange):
fig = plt.figure(figsize=(12, 7.5), layout="constrained")
for i, name in enumerate(names):
    scene = ds.load_scene(name)
    ax = fig.add_subplot(2, (len(names) + 1) // 2, i + 1, projection="3d")
    plot_robot(scene.equilibrium(), ax=ax)
    ax.get_legend().remove()
    ax.set_title(f"{name}: {len(scene.robot.cables)} cables", fontsize="medium")
plt.show()
