package io.dtron.cli;

import io.dtron.api.ServedChannels;
import io.dtron.bridge.BusRun;
import io.dtron.bridge.BusRunSequence;
import io.dtron.engine.ObservableWindow;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.PrintWriter;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;

/**
 * What {@code dtron run} prints of the steps of a bus run before time 0 ({@link BusRunSequence}), and why a run
 * does not start, with what the user can do about it. In real time with DTRON's engine it also measures the tester's
 * lateness while the adapters are probed ({@link #engineWarmUp}), and says the input margin that lateness needs.
 */
final class BusRunLines implements BusRunSequence.Steps {
    private final PrintWriter out;
    private final PrintWriter err;
    private final BusRun run;
    private final String cluster;
    private final String where;
    private final Network network;
    private final TestInterface testInterface;
    private final long unitMicros;
    private volatile SchedulingDelay lateness;

    /**
     * Lines for a run on bus {@code cluster} at {@code where} of a model with its interface at a time unit.
     */
    BusRunLines(PrintWriter out, PrintWriter err, BusRun run, String cluster, String where, Network network,
            TestInterface testInterface, long unitMicros) {
        this.out = out;
        this.err = err;
        this.run = run;
        this.cluster = cluster;
        this.where = where;
        this.network = network;
        this.testInterface = testInterface;
        this.unitMicros = unitMicros;
    }

    /** The engine's warm-up while the adapters are probed: it measures the tester's lateness meanwhile. */
    Runnable engineWarmUp() {
        return () -> lateness = SchedulingDelay.measureWarmingUp(network, testInterface);
    }

    /** The input margin the lateness measured during the warm-up needs; empty without a warm-up. */
    java.util.OptionalLong inputMarginMicros() {
        SchedulingDelay measured = lateness;
        return measured == null ? java.util.OptionalLong.empty() : java.util.OptionalLong.of(measured.marginMicros());
    }

    @Override
    public void waitingForChannels(Duration wait, List<String> missing) {
        say("dtron run: waiting up to " + wait.toSeconds() + " s until an adapter on bus '" + cluster
                + "' serves every channel of the model; missing: " + String.join(", ", missing));
    }

    @Override
    public void stillMissing(List<String> missing) {
        say("dtron run: still missing: " + String.join(", ", missing));
    }

    @Override
    public void channelsServed() {
        say("dtron run: every channel is served" + servedSummary(run));
    }

    @Override
    public void waitingForAdapters(Duration wait, int wanted) {
        say("dtron run: waiting up to " + wait.toSeconds() + " s for " + wanted + " adapter" + (wanted == 1 ? "" : "s")
                + " to join bus '" + cluster + "'");
    }

    @Override
    public void adaptersJoined(List<String> members) {
        say("dtron run: members " + members);
    }

    @Override
    public void readyToJoin(Duration wait) {
        say("dtron run: ready; waiting up to " + wait.toSeconds() + " s for the tester that starts the run on bus '"
                + cluster + "'");
    }

    @Override
    public void waitingForTesters(Duration wait, int others) {
        say("dtron run: waiting up to " + wait.toSeconds() + " s for " + others + " other tester" + (others == 1 ? ""
                : "s") + " to join the run with --join");
    }

    @Override
    public void testersJoined(List<String> testers) {
        say("dtron run: the run's testers: " + run.memberId() + " (this one), " + String.join(", ", testers));
    }

    @Override
    public void probed(BusRun.Probing probing, boolean engineWarmedUp) {
        say(BusTiming.probingLine(probing, engineWarmedUp));
    }

    /**
     * After the warm-up: says the lateness measured, and warns about input windows narrower than the room their
     * inputs need (the margin for the lateness plus each channel's delay to its adapter).
     */
    @Override
    public void warmedUp() {
        say("dtron run: " + lateness.describe(unitMicros) + ", and each input channel's delay to its adapter further"
                + " inside; inputs to adapters that hold them until their time are sent ahead by that delay instead,"
                + " and aimed inside by how late after their time the adapters applied them");
        lateness.narrowInputWindow(network, testInterface, unitMicros, "--virtual-time", run::inputDelayMicros,
                channel -> run.inputLeadMicros(channel) > 0)
                .ifPresent(warning -> {
                    err.println("dtron run: warning: " + warning);
                    err.flush();
                });
        // the warm-up's garbage is collected now, not in a pause of several milliseconds early in the run
        System.gc();
    }

    @Override
    public void delays(BusRun.Delays delays, long windowMicros, boolean automatic) {
        out.println(BusTiming.delaysLine(delays, windowMicros, automatic));
        BusTiming.windowWarning(ObservableWindow.narrowest(network, testInterface), delays, unitMicros)
                .ifPresent(out::println);
        out.flush();
    }

    /** Says why the run does not start, and what to do, in one line. */
    void refused(BusRunSequence.Refusal refusal, Duration wait) {
        long seconds = wait.toSeconds();
        List<String> names = refusal.names();
        err.println("dtron run: " + switch (refusal.reason()) {
            case OTHER_RUN -> "bus '" + cluster + "' at " + where + " has a run in progress: tester "
                    + String.join(", ", names) + " is on it, and its adapters would serve both runs. Give this run a"
                    + " bus of its own with --cluster NAME (and its adapters the same name), or wait until the other"
                    + " run is over";
            case CHANNELS_UNSERVED -> "within " + seconds + " s no adapter on bus '" + cluster + "' at " + where
                    + " served " + String.join(", ", names) + servedSummary(run) + ". Start the adapters with the"
                    + " same cluster name and address (adapters declare the channels they send with"
                    + " Dtron.declareOutputs), wait longer with --wait-timeout, or, for adapters that do not say which"
                    + " channels they serve, wait for a number of them with --wait-for-adapters N";
            case ADAPTERS_MISSING -> "only " + refusal.count() + " of " + refusal.wanted() + " adapters joined bus '"
                    + cluster + "' at " + where + " within " + seconds + " s; start them with the same cluster name"
                    + " and address, or wait longer with --wait-timeout";
            case OWNERS -> "bus '" + cluster + "' at " + where + ": " + names.get(0) + ". Stop all but one of them, or"
                    + " give this run a bus of its own with --cluster NAME (and its adapters the same name)";
            case NO_STARTING_TESTER -> "no tester that could start a run greeted bus '" + cluster + "' within "
                    + seconds + " s (this tester needs its clock's offset to that tester's); start it with --testers"
                    + " N, or wait longer with --wait-timeout";
            case TESTERS_MISSING -> "only " + refusal.count() + " of " + refusal.wanted() + " other testers joined"
                    + " the run on bus '" + cluster + "' within " + seconds + " s; start them with --join and the same"
                    + " cluster name (and --members where they are on other hosts)";
            case NO_RUN_STARTED -> "no tester started a run on bus '" + cluster + "' within " + seconds + " s; start"
                    + " it with --testers N (N counting every tester of the run), or wait longer with --wait-timeout";
            case INTERRUPTED -> "interrupted while " + names.get(0);
        });
        err.flush();
    }

    private void say(String line) {
        out.println(line);
        out.flush();
    }

    /** "; members: A receives [..] sends [..], ..." for what the adapters on the bus said they serve. */
    static String servedSummary(BusRun busRun) {
        Map<String, ServedChannels> served = busRun.servedChannels();
        if (served.isEmpty()) {
            return "; no adapter on the bus said which channels it serves (members: " + busRun.members() + ")";
        }
        List<String> parts = new ArrayList<>();
        served.forEach((member, channels) -> parts.add(member + " receives " + channels.receives() + " and sends "
                + channels.sends()));
        return "; " + String.join(", ", parts);
    }
}
