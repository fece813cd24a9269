"""The joint and body vocabulary (names.py) against the URDF generated from the shipped
parameters, its SRDF and the loaded model: every name and order the package takes from it is
the description's own."""
import xml.etree.ElementTree as ET

import pytest

from pollard_pin import names as N
from pollard_pin.model.params import load_params
from pollard_pin.model.urdf import generate_srdf, generate_urdf


@pytest.fixture(scope="module")
def urdf():
    return ET.fromstring(generate_urdf(load_params()))


def test_tree_joints_are_the_urdf_revolute_joints_in_order(urdf):
    revolute = [j.get("name") for j in urdf.iter("joint") if j.get("type") == "revolute"]
    assert tuple(revolute) == N.TREE_JOINTS


def test_chains_are_serial_in_the_urdf(urdf):
    """Each chain of CHAIN_JOINTS is a parent → child sequence of links in the URDF, and the
    chains together are the tree joints, each once."""
    joints = {j.get("name"): j for j in urdf.iter("joint")}
    assert tuple(n for _, group in N.CHAIN_JOINTS for n in group) == N.TREE_JOINTS
    assert tuple(c for c, _ in N.CHAIN_JOINTS) == ("chain 0", "wrist", "leg 1", "leg 2")
    for chain, group in N.CHAIN_JOINTS:
        for a, b in zip(group, group[1:]):
            child = joints[a].find("child").get("link")
            assert joints[b].find("parent").get("link") == child, (chain, a, b)
    assert set(N.CHAINS) == {c for c, _ in N.CHAIN_JOINTS} - {"wrist"}


def test_bodies_are_the_links_with_mass(urdf):
    massive = {link.get("name") for link in urdf.iter("link")
               if link.find("inertial") is not None
               and float(link.find("inertial").find("mass").get("value")) > 0}
    assert massive == set(N.BODIES) and len(N.BODIES) == 9


def test_actuated_and_passive_split_the_tree_and_match_the_model(robot):
    assert set(N.ACTUATED) | set(N.PASSIVE) == set(N.TREE_JOINTS)
    assert not set(N.ACTUATED) & set(N.PASSIVE) and len(N.ACTUATED) == 6
    assert robot.joint_names == N.TREE_JOINTS
    assert tuple(robot.joint_names[i] for i in robot.actuated_v) == N.ACTUATED
    assert tuple(robot.joint_names[i] for i in robot.passive_v) == N.PASSIVE
    assert tuple(robot.model.names)[1:] == N.TREE_JOINTS  # Pinocchio's order, after universe


def test_spherical_angles_are_zyz_per_leg_and_joints_add_them():
    assert N.SPHERICAL == tuple(f"{a}_{leg}" for leg in (1, 2)
                                for a in ("theta98", "theta109", "theta1110"))
    assert N.JOINTS == N.TREE_JOINTS + N.SPHERICAL and len(set(N.JOINTS)) == 18


def test_srdf_home_names_the_tree_joints():
    home = ET.fromstring(generate_srdf(load_params(), dict.fromkeys(N.TREE_JOINTS, 0.0)))
    assert tuple(j.get("name") for j in home.iter("joint")) == N.TREE_JOINTS
