#!/usr/bin/python3
"""Measures the live node suite on a simulated world played with rosbag play.

For each playback rate: simulates the world (once) with tacs_sim, starts tacs_graphs.launch on a
private ROS master, plays the bag, waits until the backend has taken everything, saves the scene
graph and stops the nodes. It samples every node's RSS and CPU time from /proc and prints a
markdown table: scans and keyframes in and out (drops), rooms, walls, loops, time to drain the
queues after the bag ended, the real-time factor, CPU per node and peak RSS per node. The RSS
time series goes to OUT/rate_<R>/memory.csv.

Needs the workspace's devel/setup.bash sourced (rosrun finds tacs_sim, roslaunch finds the
package). Example, the longest world at 1x, 2x and 4x, then a 30-minute run (6 laps) at 4x:

  scripts/live_suite_bench.py --world worlds/large_hall.json --rates 1 2 4 --out /tmp/live
  scripts/live_suite_bench.py --world worlds/large_hall.json --laps 6 --rates 4 --out /tmp/live30
"""
import argparse
import json
import os
import signal
import subprocess
import sys
import threading
import time

import yaml

NODES = ['gicp_odometry', 'traversability', 'wall_extraction', 'room_segmentation',
         'loop_closure', 'backend']
POINTS_TOPIC = '/velodyne_points'  # what tacs_sim writes
CLK_TCK = os.sysconf('SC_CLK_TCK')
QUIET_S = 5.0  # the suite has drained when no keyframe or scene graph came for this long


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    p.add_argument('--world', default='worlds/large_hall.json')
    p.add_argument('--rates', type=float, nargs='+', default=[1.0, 2.0, 4.0])
    p.add_argument('--laps', type=int, default=0, help='override the trajectory laps (0: keep)')
    p.add_argument('--seed', type=int, default=1)
    p.add_argument('--config', default='', help='pipeline YAML (default: the launch default)')
    p.add_argument('--port', type=int, default=11411, help='port of the private ROS master')
    p.add_argument('--sample-period', type=float, default=1.0, help='[s] RSS/CPU sampling')
    p.add_argument('--out', required=True)
    return p.parse_args()


class ProcSampler(threading.Thread):
    """Samples RSS (MB) and CPU time (s) of the node processes from /proc."""

    def __init__(self, period_s):
        super().__init__(daemon=True)
        self.period_s = period_s
        self.rows = []  # (wall s since start, node, rss MB)
        self.peak_mb = {}  # VmHWM: the kernel's own peak RSS
        self.cpu_s = {}
        self.stop_event = threading.Event()
        self.t0 = time.monotonic()
        self.pids = {}

    def find_pids(self):
        for pid in os.listdir('/proc'):
            if not pid.isdigit():
                continue
            try:
                with open('/proc/%s/cmdline' % pid, 'rb') as f:
                    args = f.read().split(b'\0')
            except OSError:
                continue
            for node in NODES:
                if ('__name:=%s' % node).encode() in args:
                    self.pids[node] = pid

    def sample(self):
        if len(self.pids) < len(NODES):
            self.find_pids()
        now = time.monotonic() - self.t0
        for node, pid in self.pids.items():
            try:
                with open('/proc/%s/status' % pid) as f:
                    status = dict(line.split(':', 1) for line in f if ':' in line)
                with open('/proc/%s/stat' % pid) as f:
                    stat = f.read().rsplit(')', 1)[1].split()
            except OSError:
                continue  # the process ended
            rss = int(status['VmRSS'].split()[0]) / 1024.0
            self.peak_mb[node] = int(status['VmHWM'].split()[0]) / 1024.0
            self.cpu_s[node] = (int(stat[11]) + int(stat[12])) / CLK_TCK  # utime + stime
            self.rows.append((now, node, rss))

    def run(self):
        self.t0 = time.monotonic()  # the series starts with the bag
        while not self.stop_event.wait(self.period_s):
            self.sample()


class TopicCounter(object):
    """Counts messages (raw, not deserialised) and remembers when the last one came."""

    def __init__(self, rospy, topic):
        self.count = 0
        self.last = None
        rospy.Subscriber(topic, rospy.AnyMsg, self.on_msg, queue_size=1000)

    def on_msg(self, _):
        self.count += 1
        self.last = time.monotonic()


def bag_info(bag):
    out = subprocess.run(['rosbag', 'info', '--yaml', bag], stdout=subprocess.PIPE, check=True,
                         universal_newlines=True).stdout
    info = yaml.safe_load(out)
    scans = sum(t['messages'] for t in info['topics'] if t['topic'] == POINTS_TOPIC)
    return scans, float(info['duration'])


def simulate(world, laps, seed, out):
    os.makedirs(out, exist_ok=True)
    if laps > 0:
        with open(world) as f:
            w = json.load(f)
        w['trajectory']['laps'] = laps
        world = os.path.join(out, 'world.json')
        with open(world, 'w') as f:
            json.dump(w, f)
    sim = os.path.join(out, 'sim')
    bag = os.path.join(sim, 'sequence.bag')
    if not os.path.isfile(bag):
        subprocess.run(['rosrun', 'tacs_graphs', 'tacs_sim', world, '--seed', str(seed), '--out',
                        sim], check=True)
    return bag


def wait_for_suite(master, timeout_s):
    """Waits until every node is registered, the cloud topic has its subscriber and the backend
    offers its save service."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        publishers, subscribers, services = master.getSystemState()
        registered = set(n.lstrip('/') for _, nodes in publishers + subscribers for n in nodes)
        subs = dict((t, nodes) for t, nodes in subscribers)
        if (registered.issuperset(NODES) and subs.get(POINTS_TOPIC) and
                any(name == '/backend/save' for name, _ in services)):
            return True
        time.sleep(0.5)
    return False


def run_rate(rospy, trigger, master, args, bag, rate, out):
    os.makedirs(out, exist_ok=True)
    launch = ['roslaunch', 'tacs_graphs', 'tacs_graphs.launch', 'use_sim_time:=true',
              'output_dir:=' + out]
    if args.config:
        launch.append('config:=' + os.path.abspath(args.config))
    log = open(os.path.join(out, 'launch.log'), 'w')
    proc = subprocess.Popen(launch, stdout=log, stderr=subprocess.STDOUT)
    sampler = ProcSampler(args.sample_period)
    result = {'rate': rate}
    try:
        # Every node must be up before the first scan; the connections between them follow.
        if not wait_for_suite(master, 60):
            raise RuntimeError('the nodes did not come up within 60 s; see ' + log.name)
        odom = TopicCounter(rospy, '/tacs/odom')
        keyframes = TopicCounter(rospy, '/tacs/keyframe')
        graphs = TopicCounter(rospy, '/tacs/scene_graph')
        time.sleep(2.0)
        sampler.start()
        t_play = time.monotonic() + 2.0
        # --delay: the subscribers connect to the bag's topics before the first scan goes out.
        subprocess.run(['rosbag', 'play', '--clock', '--quiet', '--delay', '2', '--rate', str(rate),
                        bag], check=True)
        t_end = time.monotonic()
        while time.monotonic() - max(keyframes.last or 0, graphs.last or 0, t_end) < QUIET_S:
            time.sleep(0.2)
        t_drained = max(keyframes.last or t_end, graphs.last or t_end, t_end)
        sampler.sample()
        processing_s = time.monotonic() - sampler.t0  # the save's OctoMap comes after
        rospy.wait_for_service('/backend/save', timeout=30)
        reply = rospy.ServiceProxy('/backend/save', trigger)()
        if not reply.success:
            raise RuntimeError('save failed: ' + reply.message)
        with open(os.path.join(out, 'scene_graph.json')) as f:
            graph = json.load(f)
        result.update({
            'play_s': t_end - t_play, 'drain_s': t_drained - t_end,
            'scans_processed': odom.count, 'keyframes_published': keyframes.count,
            'keyframes_in_graph': len(graph['keyframes']), 'rooms': len(graph['rooms']),
            'walls': len(graph['walls']), 'loops': len(graph.get('loops', [])),
        })
        result['alive'] = all(n in sampler.pids and os.path.exists('/proc/' + sampler.pids[n])
                              for n in NODES)
    finally:
        sampler.stop_event.set()
        proc.send_signal(signal.SIGINT)
        try:
            proc.wait(timeout=120)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.close()
    result['peak_mb'] = dict(sampler.peak_mb)
    result['cpu_s'] = dict(sampler.cpu_s)
    with open(os.path.join(out, 'memory.csv'), 'w') as f:
        f.write('wall_s,node,rss_mb\n')
        for t, node, rss in sampler.rows:
            f.write('%.1f,%s,%.1f\n' % (t, node, rss))
    result['rss_quartiles'] = rss_quartiles(sampler.rows, processing_s)
    with open(os.path.join(out, 'launch.log')) as f:
        text = f.read()
    result['warn_missing_scans'] = text.count('scan(s) missing')
    result['warn_lost_keyframes'] = text.count('never arrived')
    return result


def rss_quartiles(rows, end):
    """RSS of each node at 25, 50, 75 and 100 % of the bag's processing (`end` s after it began;
    the save afterwards is left out)."""
    out = {}
    for node in NODES:
        series = [(t, r) for t, n, r in rows if n == node]
        if series:
            out[node] = [next((r for t, r in series if t >= q * end - 1e-9), series[-1][1])
                         for q in (0.25, 0.5, 0.75, 1.0)]
    return out


def table(results, scans, duration):
    lines = ['Bag: %d scans, %.1f s. RTF: bag seconds / (play + drain) seconds.' % (scans, duration),
             '',
             '| rate | play s | drain s | RTF | scans processed | missing | keyframes out / in graph'
             ' | rooms | walls | loops | all nodes alive |',
             '|---|---|---|---|---|---|---|---|---|---|---|']
    for r in results:
        rtf = duration / (r['play_s'] + r['drain_s'])
        lines.append('| %gx | %.1f | %.1f | %.2f | %d / %d | %d | %d / %d | %d | %d | %d | %s |' % (
            r['rate'], r['play_s'], r['drain_s'], rtf, r['scans_processed'], scans,
            scans - r['scans_processed'], r['keyframes_published'], r['keyframes_in_graph'],
            r['rooms'], r['walls'], r['loops'], 'yes' if r['alive'] else 'NO'))
    lines += ['', 'Peak RSS includes the save after the bag (OctoMap); the RSS columns sample the bag\'s'
              ' processing at 25/50/75/100 % of its wall time.', '',
              '| rate | node | CPU s | CPU s per bag s | peak RSS MB | RSS at 25/50/75/100 % MB |',
              '|---|---|---|---|---|---|']
    for r in results:
        total = 0.0
        for node in NODES:
            cpu = r['cpu_s'].get(node, float('nan'))
            total += cpu
            q = r['rss_quartiles'].get(node, [])
            lines.append('| %gx | %s | %.1f | %.3f | %.0f | %s |' % (
                r['rate'], node, cpu, cpu / duration, r['peak_mb'].get(node, float('nan')),
                ' / '.join('%.0f' % v for v in q)))
        lines.append('| %gx | all | %.1f | %.3f | %.0f | |' % (
            r['rate'], total, total / duration, sum(r['peak_mb'].values())))
    return '\n'.join(lines)


def main():
    args = parse_args()
    out = os.path.abspath(args.out)
    os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % args.port
    bag = simulate(args.world, args.laps, args.seed, out)
    scans, duration = bag_info(bag)
    master_proc = subprocess.Popen(['roscore', '-p', str(args.port)], stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
    try:
        import rosgraph
        import rospy
        from std_srvs.srv import Trigger
        master = rosgraph.Master('/live_suite_bench')
        deadline = time.monotonic() + 30
        while not rosgraph.is_master_online():
            if time.monotonic() > deadline:
                raise RuntimeError('no ROS master on port %d' % args.port)
            time.sleep(0.5)
        rospy.init_node('live_suite_bench', disable_signals=True)
        results = []
        for rate in args.rates:
            print('[live_suite_bench] rate %gx ...' % rate, flush=True)
            results.append(run_rate(rospy, Trigger, master, args, bag, rate,
                                    os.path.join(out, 'rate_%g' % rate)))
            with open(os.path.join(out, 'results.json'), 'w') as f:
                json.dump(results, f, indent=1)
        report = table(results, scans, duration)
        with open(os.path.join(out, 'live_suite.md'), 'w') as f:
            f.write(report + '\n')
        print(report)
    finally:
        master_proc.send_signal(signal.SIGINT)
        master_proc.wait(timeout=30)
    return 0


if __name__ == '__main__':
    sys.exit(main())
