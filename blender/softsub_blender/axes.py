"""Blender (Z up) <-> softsub (Y up): the one mapping every position, direction,
rotation and mesh goes through. Pure Python, no bpy.

softsub's world is Y up (gravity 0 -9.81 0), Blender's is Z up. A point at Blender
(x, y, z) is at softsub (x, z, -y): a rotation of -90 degrees about X, the usual Y-up
convention of OBJ and glTF exporters, so both worlds stay right-handed and nothing is
mirrored. softsub's floor (y = 0) is Blender's ground plane (z = 0); softsub's +z
(towards the default camera) is Blender's -Y (towards Blender's front view).
"""
import math

Vec = tuple


def to_softsub(v):
    """A Blender position or direction (x, y, z) in softsub coordinates."""
    return (v[0], v[2], -v[1])


def to_blender(v):
    """A softsub position or direction in Blender coordinates."""
    return (v[0], -v[2], v[1])


# The rotation (Euler XYZ, radians) that shows in Blender's axes an object whose data
# stays in softsub's: +90 degrees about X takes softsub (x, y, z) to (x, -z, y), which
# is to_blender. For what is read as it is, such as a VDB grid (meshes and points are
# converted vertex by vertex instead).
SOFTSUB_TO_BLENDER_EULER = (math.pi / 2, 0.0, 0.0)


def quat_to_softsub(q):
    """A Blender rotation quaternion (w, x, y, z) in softsub coordinates."""
    return (q[0],) + to_softsub(q[1:4])


def quat_to_blender(q):
    """A softsub rotation quaternion (w, x, y, z) in Blender coordinates."""
    return (q[0],) + to_blender(q[1:4])


def quat_to_matrix(q):
    """Rotation matrix (rows) of a quaternion (w, x, y, z); normalised first."""
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return (
        (1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)),
        (2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)),
        (2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)),
    )


def matrix_to_quat(m):
    """Unit quaternion (w, x, y, z), w >= 0, of a rotation matrix (rows)."""
    t = m[0][0] + m[1][1] + m[2][2]
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        q = (0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s)
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        q = ((m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s)
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        q = ((m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s)
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        q = ((m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s)
    if q[0] < 0:
        q = tuple(-c for c in q)
    n = math.sqrt(sum(c * c for c in q))
    return tuple(c / n for c in q)


def _rot(axis, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    if axis == 0:
        return ((1, 0, 0), (0, c, -s), (0, s, c))
    if axis == 1:
        return ((c, 0, s), (0, 1, 0), (-s, 0, c))
    return ((c, -s, 0), (s, c, 0), (0, 0, 1))


def matmul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def euler_xyz_to_matrix(deg):
    """softsub's InitialRotation: degrees about X, then Y, then Z (R = Rz Ry Rx)."""
    return matmul(_rot(2, deg[2]), matmul(_rot(1, deg[1]), _rot(0, deg[0])))


def matrix_to_euler_xyz(m):
    """Degrees (x, y, z) with R = Rz Ry Rx; y in [-90, 90]."""
    sy = -m[2][0]
    sy = max(-1.0, min(1.0, sy))
    y = math.asin(sy)
    if abs(sy) < 1 - 1e-12:
        x = math.atan2(m[2][1], m[2][2])
        z = math.atan2(m[1][0], m[0][0])
    else:  # gimbal lock: put everything into x
        z = 0.0
        x = math.atan2(-m[1][2], m[1][1]) if sy > 0 else math.atan2(-m[1][2], m[1][1])
    return (math.degrees(x), math.degrees(y), math.degrees(z))


# softsub's Euler XYZ (a, b, c) about softsub's axes is, in Blender's axes, a about X,
# then b about Z, then -c about Y: Blender's rotation mode 'XZY' with the angles
# (a, -c, b). Objects imported from a .scene use that mode, so their angles survive a
# re-export exactly.
def softsub_euler_to_blender_xzy(deg):
    """softsub InitialRotation (degrees) -> Blender rotation_euler (radians) in mode 'XZY'."""
    return (math.radians(deg[0]), -math.radians(deg[2]), math.radians(deg[1]))


def blender_xzy_to_softsub_euler(rad):
    """Blender rotation_euler (radians, mode 'XZY') -> softsub InitialRotation (degrees)."""
    return (math.degrees(rad[0]), math.degrees(rad[2]), -math.degrees(rad[1]))


def blender_matrix_to_softsub_euler(m):
    """A Blender rotation matrix (rows) -> softsub InitialRotation (degrees)."""
    q = quat_to_softsub(matrix_to_quat(m))
    return matrix_to_euler_xyz(quat_to_matrix(q))
