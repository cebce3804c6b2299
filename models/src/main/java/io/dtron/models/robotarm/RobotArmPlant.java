package io.dtron.models.robotarm;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.RunClock;
import java.net.InetAddress;
import java.nio.file.Path;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.CountDownLatch;
import java.util.function.Consumer;

/**
 * The robot arm of the control sample ({@code robot-arm.xta}) as a plant on the bus, in Java: the twin of the Python
 * plant {@code clients/python/examples/robot_arm.py}, for the embedded JGroups bus (the Python client speaks NATS
 * only). It takes the controller's commands {@code move}, {@code grip}, {@code release} and {@code stop}, and its
 * sensors answer on the run clock: {@code arrived} 3 time units after a move was applied (the model allows 2 to 5),
 * {@code gripped} 1 unit after a grip (1 to 2). A command the arm cannot take in its state is reported and ignored;
 * {@code stop}, the safe action, is taken in every state and stops the arm until the next run. A stalling arm never
 * arrives.
 *
 * <p>As a process: {@code java -cp ... io.dtron.models.robotarm.RobotArmPlant --cluster NAME [--key-file FILE]
 * [--stall] [--runs N]} joins the JGroups bus {@code NAME} on loopback and prints {@code stopped at t=...} when it
 * takes stop and {@code ignored: ...} for a command it cannot take; with {@code --runs N} it leaves after N runs.
 */
public final class RobotArmPlant implements DtronAdapter {
    static final IDtronChannel MOVE = IDtronChannel.of("move");
    static final IDtronChannel GRIP = IDtronChannel.of("grip");
    static final IDtronChannel RELEASE = IDtronChannel.of("release");
    static final IDtronChannel STOP = IDtronChannel.of("stop");
    static final IDtronChannel ARRIVED = IDtronChannel.of("arrived");
    static final IDtronChannel GRIPPED = IDtronChannel.of("gripped");
    /** Time units from a move to its arrival, and from a grip to its reading: inside the model's windows. */
    static final double TRAVEL = 3;
    static final double GRIP_TIME = 1;

    private enum State { READY, MOVING, ARRIVED, GRIPPING, HOLDING, STOPPED }

    private final boolean stall;
    private final Consumer<String> report;
    private Dtron dtron;
    private State state = State.READY;
    private RunClock.Task sensing;

    /**
     * An arm that reports what it stopped at and what it ignored to {@code report}; a stalling one ({@code stall})
     * never arrives.
     */
    public RobotArmPlant(boolean stall, Consumer<String> report) {
        this.stall = stall;
        this.report = report;
    }

    @Override
    public synchronized void start(Dtron bus) {
        dtron = bus;
        bus.declareOutputs(ARRIVED, GRIPPED);
        listen(Dtron.RUN_START, m -> begin());
        listen(MOVE, m -> {
            if (expect(State.READY, m)) {
                state = State.MOVING;
                if (!stall) {
                    after(TRAVEL, ARRIVED, State.ARRIVED);
                }
            }
        });
        listen(GRIP, m -> {
            if (expect(State.ARRIVED, m)) {
                state = State.GRIPPING;
                after(GRIP_TIME, GRIPPED, State.HOLDING);
            }
        });
        listen(RELEASE, m -> {
            if (expect(State.HOLDING, m)) {
                state = State.READY;
            }
        });
        listen(STOP, m -> {
            cancel();
            state = State.STOPPED;
            report.accept(String.format(Locale.ROOT, "stopped at t=%.3f", dtron.runClock().nowUnits()));
        });
    }

    private void listen(IDtronChannel channel, Consumer<IDtronChannelValued> action) {
        dtron.addDtronListener(new DtronListener(channel) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                synchronized (RobotArmPlant.this) {
                    action.accept(message);
                }
            }
        });
    }

    /** A run starts: the arm is ready, nothing in its hand. */
    private void begin() {
        cancel();
        state = State.READY;
    }

    private boolean expect(State wanted, IDtronChannelValued command) {
        if (state != wanted) {
            report.accept("ignored: " + command.getChannelName() + " in state " + state);
            return false;
        }
        return true;
    }

    /** The sensor's {@code reading} {@code units} after now on the run clock, the arm then in {@code next}. */
    private void after(double units, IDtronChannel reading, State next) {
        cancel();
        RunClock clock = dtron.runClock();
        double due = clock.nowUnits() + units;
        RunClock.Task[] task = new RunClock.Task[1];
        task[0] = clock.scheduleAt(due, () -> sense(task[0], reading, next));
        sensing = task[0];
    }

    private synchronized void sense(RunClock.Task task, IDtronChannel reading, State next) {
        if (task == null || task != sensing || task.isCancelled()) {
            return;
        }
        long happened = dtron.currentTimeNanos(); // the sensor fires now; publishing takes a moment more
        state = next;
        try {
            dtron.send(reading.constructValued(Map.of()), happened);
        } catch (DtronException | IllegalStateException e) {
            report.accept("cannot send " + reading.getChannelName() + ": " + e.getMessage());
        }
    }

    private void cancel() {
        if (sensing != null) {
            sensing.cancel();
            sensing = null;
        }
    }

    @Override
    public synchronized void close() {
        cancel();
    }

    /** The arm as a process on the JGroups bus on loopback; the options are those of the class comment. */
    public static void main(String[] args) throws InterruptedException {
        String cluster = DtronOptions.DEFAULT_CLUSTER;
        Path keyFile = null;
        boolean stall = false;
        int runs = 0;
        for (int a = 0; a < args.length; a++) {
            switch (args[a]) {
                case "--cluster" -> cluster = value(args, ++a);
                case "--key-file" -> keyFile = Path.of(value(args, ++a));
                case "--stall" -> stall = true;
                case "--runs" -> runs = count(value(args, ++a));
                default -> {
                    System.err.println("robot arm: unknown option " + args[a] + " (--cluster NAME, --key-file FILE,"
                            + " --stall, --runs N)");
                    System.exit(1);
                }
            }
        }
        DtronOptions.Builder options = DtronOptions.builder().clusterName(cluster)
                .bindAddress(InetAddress.getLoopbackAddress());
        if (keyFile != null) {
            options.keyFile(keyFile);
        }
        CountDownLatch over = new CountDownLatch(Math.max(runs, 1));
        try (Dtron bus = Dtron.connect(options.build());
             RobotArmPlant arm = new RobotArmPlant(stall, line -> {
                 System.out.println(line);
                 System.out.flush();
             })) {
            arm.start(bus);
            bus.addDtronListener(new DtronListener(Dtron.RUN_STOP) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    over.countDown();
                }
            });
            System.out.println("robot arm" + (stall ? " (stalling)" : "") + " joined bus '" + cluster + "' as "
                    + bus.getMemberId());
            System.out.flush();
            if (runs > 0) {
                over.await();
            } else {
                new CountDownLatch(1).await();
            }
        } catch (DtronException e) {
            System.err.println("robot arm: " + e.getMessage());
            System.exit(1);
        }
    }

    private static int count(String text) {
        if (!text.matches("\\d{1,6}")) {
            System.err.println("robot arm: --runs must be a number of runs: " + text);
            System.exit(1);
        }
        return Integer.parseInt(text);
    }

    private static String value(String[] args, int at) {
        if (at >= args.length) {
            System.err.println("robot arm: " + args[at - 1] + " needs a value");
            System.exit(1);
        }
        return args[at];
    }
}
