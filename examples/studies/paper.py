"""The values the paper reports (rmtr-subdivision-cloth, §7), for side-by-side tables.

None marks a cell the paper leaves empty (the solver did not converge or was not run).
"""

SCENES = ("trampoline", "drooping", "reentrant_corner", "drape")
DOFS = (147, 363, 1083, 3675, 13467, 51483)

# Table 3: single-level TR iterations vs dofs, dt = 1.
TR_ITERATIONS = {
    "trampoline": (1385, 29426, 34456, None, None, None),
    "drooping": (1976, 43475, 15444, 12792, None, None),
    "reentrant_corner": (8293, 13965, 18873, 47536, 334463, None),
    "drape": (7331, 53654, 175132, None, None, None),
}

# Table 4: RMTR V-cycles vs number of levels 2..6 (finest 363 ... 51,483 dofs), dt = 1.
LEVELS = (2, 3, 4, 5, 6)
RMTR_CYCLES = {
    "trampoline": (633, 150, 81, 88, 52),
    "drooping": (4671, 645, 707, 1636, 333),
    "reentrant_corner": (3188, 1508, 282, 124, 30),
    "drape": (9732, 7653, 5718, 792, 423),
}

# Tables 6 and 7: work units (eq. 7.3) at 1,083 dofs, RMTR with three levels:
# (TR total, RMTR total, TR per iteration, RMTR per V-cycle).
ASSEMBLY_WORK = {
    "trampoline": (30981, 370, 0.89, 2.47),
    "drooping": (13858, 1612, 0.90, 2.50),
    "reentrant_corner": (16632, 3788, 0.88, 2.51),
    "drape": (120089, 19163, 0.69, 2.50),
}
QP_WORK = {
    "trampoline": (34456, 370, 1.0, 2.47),
    "drooping": (15444, 1612, 1.0, 2.50),
    "reentrant_corner": (18873, 3788, 1.0, 2.51),
    "drape": (175132, 19163, 1.0, 2.50),
}

# Table 8: V-cycles at 3,675 dofs, four levels: (least-squares fit, reverse subdivision).
PROJECTION_CYCLES = {
    "trampoline": (84, 81),
    "drooping": (659, 707),
    "reentrant_corner": (277, 282),
    "drape": (5691, 5718),
}

# Figure 9 (read from the text, not the plot): cond(H) > 1e8 at every resolution, about 1e13
# at ~50,000 dofs, and independent of beta below 1e5 (trampoline, 1,083 dofs, dt = 1).
CONDITION_NOTES = ("cond(H) > 1e8 at all resolutions; ~1e13 at ~50,000 dofs; "
                   "flat in beta for beta < 1e5, growing above")

# Figure 10: every trust-region solver converges at every dt in 1/24 ... 1 for all scenes; the
# text gives no numbers for the others, which need smaller steps.
TIMESTEPS = (1 / 24, 1 / 12, 1 / 6, 1 / 3, 1 / 2, 1.0)


def levels_for_refine(refine):
    """Number of RMTR levels at a finest refinement: the cage and each refinement of it, as in
    the paper (2 levels: one refinement of the coarsest cage)."""
    return int(refine) + 1
