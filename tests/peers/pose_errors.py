#!/usr/bin/env python3
"""Position RMSE / max and heading RMSE of an estimated path against a TUM truth.

Exists for tests/peers/mrpt_pf_localization.sh (issue 12's side-by-side peer): one
evaluator for both localisers, so that MRPT's figures and structloc's are computed
the same way on the same truth poses.

  pose_errors.py tum EST.tum TRUTH.tum       estimate given as TUM, matched by stamp
  pose_errors.py mrpt-log PF.out TRUTH.tum [--skip N] [--shift DX DY] [--tum-out EST.tum]
                                             estimate = the "PDF estimation: (x,y,phi deg)"
                                             lines pf-localization logs, one per rawlog entry,
                                             in scan order, which is the truth's order;
                                             --skip N drops the first N of them (the script's
                                             rawlog starts with a lead-in pair: pf-localization
                                             runs no filter step on its first entry);
                                             --shift DX DY is subtracted from every estimate
                                             (the grid's origin as MRPT rounded it minus the
                                             map_server origin)

Prints one line: "<n> <rmse_m> <max_m> <heading_rmse_deg>". Exits 1 on unusable input.
"""
import math
import re
import sys


def yaw_from_quaternion(qx, qy, qz, qw):
    return math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))


def read_tum(path):
    poses = []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            if len(fields) != 8:
                sys.exit(f"{path}: a TUM line needs 8 fields 't x y z qx qy qz qw': {line.strip()}")
            t, x, y, _, qx, qy, qz, qw = map(float, fields)
            poses.append((t, x, y, yaw_from_quaternion(qx, qy, qz, qw)))
    return poses


ESTIMATE = re.compile(r"PDF estimation: \(([-0-9.eE+]+),([-0-9.eE+]+),([-0-9.eE+]+)deg\)")


def read_mrpt_log(path, truth, skip=0, shift=(0.0, 0.0)):
    with open(path, errors="replace") as f:
        found = [m.groups() for m in map(ESTIMATE.search, f) if m][skip:]
    if len(found) != len(truth):
        sys.exit(f"{path}: {len(found)} pose estimates (after skipping {skip}) for {len(truth)} truth "
                 "poses; pf-localization did not run through the whole rawlog")
    return [(t[0], float(x) - shift[0], float(y) - shift[1], math.radians(float(phi)))
            for t, (x, y, phi) in zip(truth, found)]


def write_tum(path, poses):
    with open(path, "w") as f:
        f.write("# timestamp x y z qx qy qz qw\n")
        for t, x, y, yaw in poses:
            f.write(f"{t:.6f} {x:.6f} {y:.6f} 0 0 0 {math.sin(yaw / 2):.9f} {math.cos(yaw / 2):.9f}\n")


def errors(estimate, truth):
    truth_by_stamp = {round(t, 4): (x, y, yaw) for t, x, y, yaw in truth}
    sq_pos, sq_yaw, worst, n = 0.0, 0.0, 0.0, 0
    for t, x, y, yaw in estimate:
        ref = truth_by_stamp.get(round(t, 4))
        if ref is None:
            continue
        d = math.hypot(x - ref[0], y - ref[1])
        dyaw = math.atan2(math.sin(yaw - ref[2]), math.cos(yaw - ref[2]))
        sq_pos += d * d
        sq_yaw += dyaw * dyaw
        worst = max(worst, d)
        n += 1
    if n == 0:
        sys.exit("no estimated pose has a truth pose with the same stamp")
    return n, math.sqrt(sq_pos / n), worst, math.degrees(math.sqrt(sq_yaw / n))


def main(argv):
    if len(argv) < 4 or argv[1] not in ("tum", "mrpt-log"):
        sys.exit(__doc__)
    truth = read_tum(argv[3])
    if argv[1] == "tum":
        if len(argv) != 4:
            sys.exit(__doc__)
        estimate = read_tum(argv[2])
    else:
        skip, shift, tum_out, rest = 0, (0.0, 0.0), None, argv[4:]
        try:
            while rest:
                if rest[0] == "--skip":
                    skip, rest = int(rest[1]), rest[2:]
                elif rest[0] == "--shift":
                    shift, rest = (float(rest[1]), float(rest[2])), rest[3:]
                elif rest[0] == "--tum-out":
                    tum_out, rest = rest[1], rest[2:]
                else:
                    sys.exit(__doc__)
        except (IndexError, ValueError):
            sys.exit(__doc__)
        estimate = read_mrpt_log(argv[2], truth, skip, shift)
        if tum_out:
            write_tum(tum_out, estimate)
    n, rmse, worst, heading = errors(estimate, truth)
    print(f"{n} {rmse:.4f} {worst:.4f} {heading:.3f}")


if __name__ == "__main__":
    main(sys.argv)
