"""rviz in a virtual X display for the rostests: start it with a config, take screenshots, count
pixels of a colour."""
import os
import shutil
import subprocess
import tempfile


class RvizUnderXvfb:
    TOOLS = ('Xvfb', 'rviz', '/usr/bin/import', '/usr/bin/convert')

    def __init__(self, config):
        missing = [t for t in self.TOOLS if shutil.which(t) is None]
        if missing:
            raise AssertionError('%s not installed (.ci/run installs them)' % ', '.join(missing))
        self.folder = tempfile.mkdtemp()
        read_end, write_end = os.pipe()
        self.xvfb = subprocess.Popen(['Xvfb', '-displayfd', str(write_end), '-screen', '0',
                                      '1024x768x24', '+extension', 'GLX', '+render', '-noreset'],
                                     pass_fds=[write_end], stderr=subprocess.DEVNULL)
        os.close(write_end)
        with os.fdopen(read_end) as display:
            self.display = ':' + display.readline().strip()
        environment = dict(os.environ, DISPLAY=self.display)
        self.rviz = subprocess.Popen(['rviz', '-d', config], env=environment,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def screenshot(self):
        """A PNG of the whole screen now (its path), or None if none could be taken."""
        shot = os.path.join(self.folder, 'rviz.png')
        if os.path.exists(shot):
            os.remove(shot)
        subprocess.run(['/usr/bin/import', '-display', self.display, '-window', 'root', shot],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return shot if os.path.exists(shot) else None

    def close(self):
        for process in (self.rviz, self.xvfb):  # rviz first: it aborts if the display goes
            process.terminate()
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()


# The 3D view of a 1024 x 768 rviz window with the displays panel docked left (the panel's blue
# text and icons must not count).
RENDER_AREA = '640x670+366+64'


def count_pixels(png, is_wanted, area=RENDER_AREA):
    """How many pixels of the PNG's `area` (ImageMagick geometry) satisfy is_wanted(r, g, b), each
    0..255."""
    raw = subprocess.run(['/usr/bin/convert', png, '-crop', area, '+repage', '-depth', '8', 'rgb:-'],
                         capture_output=True, check=True).stdout
    return sum(1 for k in range(0, len(raw), 3) if is_wanted(raw[k], raw[k + 1], raw[k + 2]))


def is_mesh_orange(r, g, b):
    """A body's surface in the markers' orange (1.0, 0.55, 0.1), lit or in shade; not the red fixed
    nodes."""
    return r > 80 and 0.35 * r < g < 0.75 * r and b < 0.3 * r


# Colours of config/grasp_demo.rviz and grasp_friction.rviz, lit or in shade.
def is_strain_coloured(r, g, b):
    """A body's surface: strain colours (s, 0.2, 1 - s)."""
    return max(r, b) > 70 and g < 0.45 * max(r, b)


def is_reaction_cyan(r, g, b):
    """The fingers' wrench arrows."""
    return g > 90 and b > 90 and r < 0.45 * min(g, b)


def is_table_wood(r, g, b):
    """The demo table's wood (0.6, 0.45, 0.3): the top in shade, the sides lit; not the grey
    background, the gripper or the strain colours."""
    return r > 30 and 0.65 * r < g < 0.85 * r and 0.4 * r < b < 0.62 * r


def is_gripper_grey(r, g, b):
    return min(r, g, b) > 120 and max(r, g, b) - min(r, g, b) < 20
