"""subprocess.run for the tests: a command that fails raises an AssertionError holding its exit
code and the end of its stdout and stderr. subprocess's own CalledProcessError names neither, so
a rostest whose ply_slam_synth exited 1 kept nothing of why (issue #53)."""
import subprocess

KEPT_CHARS = 4000  # of each stream, from its end


def run(command, **kwargs):
    """Runs `command` (a list), its output captured as text; returns the CompletedProcess."""
    done = subprocess.run(command, capture_output=True, text=True, **kwargs)
    if done.returncode != 0:
        raise AssertionError("%s exited with %d\n--- stdout (end):\n%s\n--- stderr (end):\n%s" % (
            " ".join(command), done.returncode, done.stdout[-KEPT_CHARS:],
            done.stderr[-KEPT_CHARS:]))
    return done
