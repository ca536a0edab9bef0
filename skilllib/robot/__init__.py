"""From a prototype's hand velocity to a robot arm's joints: the paper's Sect. 7 and beyond.

The arms and their limits (``_arms``: Simple6, UR5, Puma 560, Panda), their reach (``_reach``), inverse
kinematics (``_ik``), the velocity transfer qdot = J(q)^-1 v (``_velocity``: :func:`transfer`), joint
accelerations, jerks and torques (``_dynamics``), the executed motion (``_execution``) and the verdict
against every limit with its time scaling (``_feasibility``: :func:`assess`), and the checks the
chapters print (``_checks``: joint limits, the tool velocity J qd, the next band frequency).
"""

import lazy_loader as _lazy

__getattr__, __dir__, __all__ = _lazy.attach(
    __name__,
    submod_attrs={
        "_arms": [
            "default_pose",
            "DEFAULT_POSE_DEG",
            "dynamic_limits",
            "GENERIC_QD_LIMIT",
            "get_robot",
            "has_dynamics",
            "joint_origins",
            "PANDA_QD_LIMITS",
            "PANDA_QDDD_LIMITS",
            "PUMA560_TAU_LIMITS",
            "qd_limits_vector",
            "ROBOT_NAMES",
            "Arm",
            "simple6",
        ],
        "_checks": ["next_band_frequency", "tool_velocity_error", "within_joint_limits"],
        "_dynamics": [
            "derivative",
            "jacobian_dot",
            "joint_accelerations",
            "joint_dynamics",
            "JointDynamics",
            "LIMIT_NAMES",
        ],
        "_execution": ["ACTUATOR_BANDWIDTH_HZ", "CONTROL_RATE_HZ", "execute"],
        "_feasibility": ["assess", "assess_one", "Assessment", "limits_text", "MAX_TIME_SCALE", "transfer_block"],
        "_ik": ["IK_CHAIN", "IK_RESTARTS", "IKAnswer", "pose_residual", "solve_ik"],
        "_reach": ["joint_axes", "reach_shell", "REACH_TOL_M", "shoulder_point"],
        "_sensitivity": [
            "feasible_counts",
            "limit_margin",
            "limit_margins",
            "limit_sensitivity",
            "LIMIT_UNITS",
            "LimitMargin",
            "verdict_range",
            "VerdictRange",
        ],
        "_velocity": [
            "apply_time_scale",
            "BRANCH_JUMP_RAD",
            "COND_THRESHOLD",
            "EXP_TO_BASE",
            "IK_RESIDUAL_TOL_M",
            "JOINT_LIMIT_TOL_RAD",
            "QD_LIMIT_RTOL",
            "SINGULAR_COND",
            "time_scale_factor",
            "time_scaled_features",
            "to_base_frame",
            "transfer",
            "transfer_summary",
            "TransferResult",
        ],
    },
)
