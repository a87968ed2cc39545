import sys, rospy, time, threading
import fake_tb3_bench as b
orig=b.run_simulator
core=b.start_master()
try:
    rospy.init_node('x', disable_signals=True)
    spawn = {'name': 'tb3_0', 'model': 'burger', 'x_pos': -2.0, 'y_pos': -0.5, 'yaw': 0.0}
    C=b.TopicCounter
    class T(C):
        def close(self):
            sim=(self.clock[-1][1]-self.start).to_sec()
            print({k: round(v/(b.TOPIC_RATES[k[1]][1]*sim),3) for k,v in self.counts.items()}, 'clock msgs', len(self.clock), flush=True)
            C.close(self)
    b.TopicCounter=T
    print(b.run_simulator("bench_one", float(sys.argv[1]), [spawn], 5.0, raw=True), flush=True)
finally:
    b.stop_process_group(core, 30)
