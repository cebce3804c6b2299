package io.dtron.engine.internal.tester;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import java.util.concurrent.TimeUnit;
import org.openjdk.jmh.annotations.Benchmark;
import org.openjdk.jmh.annotations.BenchmarkMode;
import org.openjdk.jmh.annotations.Fork;
import org.openjdk.jmh.annotations.Level;
import org.openjdk.jmh.annotations.Measurement;
import org.openjdk.jmh.annotations.Mode;
import org.openjdk.jmh.annotations.OutputTimeUnit;
import org.openjdk.jmh.annotations.Param;
import org.openjdk.jmh.annotations.Scope;
import org.openjdk.jmh.annotations.Setup;
import org.openjdk.jmh.annotations.State;
import org.openjdk.jmh.annotations.Warmup;

/**
 * State-set updates of the online tester, one step of a recorded run at a time: the delay to an observation
 * plus the observed move ({@link #observe}), and the planning of the next step ({@link #plan}). The run is
 * recorded by letting the model drive itself (earliest output, else an input the environment allows), so every
 * step is one the tester really meets. JMH forks JVMs, so run it from a plain java command with the test
 * classpath (see {@code src/site/markdown/benchmarks.md}).
 */
@State(Scope.Benchmark)
@BenchmarkMode(Mode.SampleTime)
@OutputTimeUnit(TimeUnit.MICROSECONDS)
@Warmup(iterations = 3, time = 2)
@Measurement(iterations = 5, time = 2)
@Fork(1)
public class StateSetBenchmark {
    private static final int TICKS = 1000;

    /** LightContr (TRON's smart lamp) or a model of eight independent nondeterministic timers. */
    @Param({"lightcontr", "timers"})
    public String model;

    private final List<Step> steps = new ArrayList<>();
    private Semantics semantics;
    private Partition partition;
    private TestInterface iface;
    private int next;

    /** One recorded step: the set before it, the delay and the observable channel taken. */
    record Step(StateSet before, long delay, int channel) {
    }

    @Setup(Level.Trial)
    public void record() throws Exception {
        Network network;
        if (model.equals("lightcontr")) {
            Path tron = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
            network = ModelLoader.load(tron.resolve("LightContr.xml"));
            iface = TestInterface.fromFile(network, tron.resolve("LightContr.trn"));
        } else {
            network = ModelLoader.load("timers.xta", timers(8));
            iface = TestInterface.fromNames(network);
        }
        semantics = new Semantics(network, TICKS);
        partition = Partition.of(network, iface);
        StateSet set = StateSet.initial(semantics, partition);
        Random random = new Random(1);
        for (int i = 0; i < 200; i++) {
            Plan plan = Plan.of(set, semantics, partition, iface, 1000, 100_000L * TICKS);
            long delay = -1;
            int channel = -1;
            for (TestInterface.ObservableChannel o : iface.outputs()) {
                for (Plan.Window w : plan.windowsOf(o.channel())) {
                    if (delay < 0 || w.lo() < delay) {
                        delay = w.lo();
                        channel = o.channel();
                    }
                }
            }
            Plan.Choice choice = plan.choose(0, random, DelayPolicy.RANDOM, 0, c -> 0);
            if (choice.isInput() && (delay < 0 || choice.ticks() < delay)) {
                delay = choice.ticks();
                channel = choice.input().channel();
            }
            if (channel < 0) {
                break;
            }
            int c = channel;
            StateSet at = set.after(delay);
            List<StateSet.Successor> succ = at.successors(c);
            if (succ.isEmpty()) {
                break;
            }
            steps.add(new Step(set, delay, channel));
            set = at.of(succ.stream().map(StateSet.Successor::state).toList());
        }
        if (steps.size() < 20) {
            throw new IllegalStateException("recorded only " + steps.size() + " steps of " + model);
        }
    }

    /** A network of {@code n} timers that may fire (an output) any time in [2, 10] after they were set. */
    static String timers(int n) {
        StringBuilder sb = new StringBuilder("chan i_set, o_fire[" + n + "];\n");
        sb.append("process Env() { state E; init E; trans E -> E { sync i_set!; }");
        for (int i = 0; i < n; i++) {
            sb.append(", E -> E { sync o_fire[").append(i).append("]?; }");
        }
        sb.append("; }\n");
        for (int i = 0; i < n; i++) {
            sb.append("process T").append(i).append("() { clock x; state Idle, Set { x <= 10 }; init Idle;")
                    .append(" trans Idle -> Set { sync i_set?; assign x = 0; },")
                    .append(" Set -> Idle { guard x >= 2; sync o_fire[").append(i).append("]!; },")
                    .append(" Set -> Set { sync i_set?; }; }\n");
        }
        sb.append("system Env");
        for (int i = 0; i < n; i++) {
            sb.append(", T").append(i);
        }
        return sb.append(";\n").toString();
    }

    /** The model's network and interface, and the state sets of the recorded steps, for other benches. */
    List<StateSet> recordedSets() {
        return steps.stream().map(Step::before).toList();
    }

    Semantics semantics() {
        return semantics;
    }

    Partition partition() {
        return partition;
    }

    TestInterface testInterface() {
        return iface;
    }

    private Step nextStep() {
        Step s = steps.get(next);
        next = (next + 1) % steps.size();
        return s;
    }

    /** Delay to the observation and take the observed move: the tester's update per event. */
    @Benchmark
    public StateSet observe() {
        Step s = nextStep();
        StateSet at = s.before().after(s.delay());
        return at.of(at.successors(s.channel()).stream().map(StateSet.Successor::state).toList());
    }

    /** Plan the next step: windows of every observable channel and the deadline. */
    @Benchmark
    public Plan plan() {
        return Plan.of(nextStep().before(), semantics, partition, iface, 1000, 100_000L * TICKS);
    }
}
