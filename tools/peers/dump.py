"""Writes the model Pinocchio reads from a URDF as plain text, for the timing programs
(peer_model.hpp reads it back), so that they need no URDF parser of their own.

usage: dump.py ROBOT.urdf > MODEL.txt

Line 1: the number of joints. Then one line per joint, in Pinocchio's order:

    KIND [ux uy uz] PARENT R(9 entries, row-major) p(3) MASS COM(3) I(9 entries, row-major)

KIND is RX, RY, RZ, PX, PY, PZ (revolute or prismatic about a frame axis) or RU / PU followed by
the unit axis; PARENT is the parent joint's index (0: the universe); R and p place the joint in
its parent; MASS, COM and I are the body's inertia (I about the centre of mass). Every number is
written by repr(), so it reads back bit for bit. Joints other than one-axis revolute and
prismatic ones (a free-flyer, a spherical joint) are refused.
"""
import sys

import pinocchio as pin

AXIS_KINDS = {
    "JointModelRX": "RX", "JointModelRY": "RY", "JointModelRZ": "RZ",
    "JointModelPX": "PX", "JointModelPY": "PY", "JointModelPZ": "PZ",
    # Continuous joints are revolute joints for the dynamics.
    "JointModelRUBX": "RX", "JointModelRUBY": "RY", "JointModelRUBZ": "RZ",
}
UNALIGNED_KINDS = {"JointModelRevoluteUnaligned": "RU", "JointModelPrismaticUnaligned": "PU"}


def numbers(values):
    return " ".join(repr(float(v)) for v in values)


def joint_line(model, j):
    joint = model.joints[j]
    kind = joint.shortname()
    if kind in AXIS_KINDS:
        head = AXIS_KINDS[kind]
    elif kind in UNALIGNED_KINDS:
        head = UNALIGNED_KINDS[kind] + " " + numbers(joint.extract().axis)
    else:
        sys.exit(f"dump.py: joint {model.names[j]} is a {kind}, which the timing programs do not read")
    placement, inertia = model.jointPlacements[j], model.inertias[j]
    values = ([model.parents[j]] + list(placement.rotation.flatten()) + list(placement.translation)
              + [inertia.mass] + list(inertia.lever) + list(inertia.inertia.flatten()))
    return head + " " + numbers(values)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: dump.py ROBOT.urdf")
    model = pin.buildModelFromUrdf(sys.argv[1])
    lines = [str(model.njoints - 1)] + [joint_line(model, j) for j in range(1, model.njoints)]
    print("\n".join(lines))


if __name__ == "__main__":
    main()
