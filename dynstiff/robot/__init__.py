"""The robot as data, its kinematics and its statics: the platform and its mass matrix,
poses, the robot (anchors, attachments, cables, platform), the equilibrium record and the
tension distribution, inverse and forward statics."""
