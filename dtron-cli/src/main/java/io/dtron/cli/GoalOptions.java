package io.dtron.cli;

import io.dtron.engine.GoalStatus;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.Steering;
import io.dtron.engine.SteeringReport;
import io.dtron.engine.Strategy;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.function.Function;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;

/**
 * The test purposes and the strategy of {@code dtron run} ({@code --goal}, {@code --goals}, {@code --strategy},
 * {@code --horizon}, {@code --fairness}), mixed into it: the steering they make, the goals said before the run and
 * the report after it.
 */
final class GoalOptions {
    @Option(names = "--goal", paramLabel = "'E<> P'",
            description = "A test purpose, an E<> query in Uppaal's syntax (repeatable). The run ends PASSED when every"
                    + " goal is reached, INCONCLUSIVE when one can no longer be (said before the run when the model"
                    + " checker proves it unreachable).")
    private List<String> goals = List.of();

    @Option(names = "--goals", paramLabel = "FILE.q",
            description = "Test purposes from a query file, one E<> query a line.")
    private Path goalFile;

    @Option(names = "--strategy", paramLabel = "random|coverage|goal", defaultValue = "random",
            description = "How inputs and their times are chosen: at random by the delay policy (the default),"
                    + " toward the nearest edge not yet covered (coverage), or toward the nearest goal (goal).")
    private String strategy;

    @Option(names = "--horizon", paramLabel = "N",
            description = "How many moves ahead --strategy coverage or goal looks (default: "
                    + Steering.DEFAULT_HORIZON + ").")
    private Integer horizon;

    @Option(names = "--fairness", paramLabel = "K",
            description = "End the run INCONCLUSIVE when a choice of the system has alternatives taken a number of"
                    + " times that differ by more than K while a goal needs the starved one.")
    private Integer fairness;

    private Steering steering;
    /** Where each goal was given: {@code --goal}, or {@code --goals FILE: line N}. */
    private final List<String> origins = new ArrayList<>();
    private OnlineTester steered;

    /**
     * Reads the options: the steering they ask for, or null when they ask for none. With a stop condition ({@code
     * --until}) the run does not end when the goals are done: the condition says when (its {@code reached(N)} asks
     * these goals).
     */
    Steering prepare(boolean until, Function<String, ParameterException> usage) {
        steering = steering(until, usage);
        return steering;
    }

    /** The goals for the stop condition's {@code reached(N)}: numbered from 1, reached as the steered run says. */
    io.dtron.engine.coverage.Goals goals() {
        int count = steering == null ? 0 : steering.goals().size();
        return new io.dtron.engine.coverage.Goals() {
            @Override
            public int count() {
                return count;
            }

            @Override
            public boolean reached(int goal) {
                return steered != null && steered.goalReached(goal - 1);
            }

            @Override
            public String describe(int goal) {
                return "goal " + goal + " '" + steering.goals().get(goal - 1) + "'";
            }
        };
    }

    private Steering steering(boolean until, Function<String, ParameterException> usage) {
        Strategy s = switch (strategy.toLowerCase(Locale.ROOT)) {
            case "random" -> Strategy.RANDOM;
            case "coverage" -> Strategy.COVERAGE;
            case "goal" -> Strategy.GOAL;
            default -> throw usage.apply("unknown strategy '" + strategy + "' (use random, coverage or goal)");
        };
        List<String> all = new ArrayList<>(goals);
        origins.clear();
        goals.forEach(g -> origins.add("--goal"));
        if (goalFile != null) {
            String text;
            try {
                text = Files.readString(goalFile, StandardCharsets.UTF_8);
            } catch (IOException e) {
                throw usage.apply("--goals " + goalFile + ": cannot read it (" + e.getMessage() + ")");
            }
            for (Query q : Query.parseFile(text)) {
                if (q.kind() == Query.Kind.INVALID) {
                    throw usage.apply("--goals " + goalFile + ": " + q.reason());
                }
                all.add(q.text());
                origins.add("--goals " + goalFile + ": line " + q.line());
            }
        }
        if (s == Strategy.GOAL && all.isEmpty()) {
            throw usage.apply("--strategy goal needs a goal: give --goal 'E<> P' or --goals FILE.q");
        }
        if (s == Strategy.RANDOM && all.isEmpty() && horizon == null && fairness == null) {
            return null;
        }
        if (horizon != null && horizon < 1) {
            throw usage.apply("--horizon must be at least 1 move: " + horizon);
        }
        if (fairness != null && fairness < 0) {
            throw usage.apply("--fairness must be 0 or more: " + fairness);
        }
        return new Steering(s, all, horizon == null ? Steering.DEFAULT_HORIZON : horizon,
                fairness == null ? -1 : fairness, !until);
    }

    /**
     * Steers {@code tester} as {@link #prepare prepared} (nothing when no steering was asked for) and says, before the
     * run, the goals the model checker proves unreachable.
     */
    void apply(OnlineTester tester, PrintWriter out, Function<String, ParameterException> usage) {
        if (steering == null) {
            return;
        }
        steered = tester;
        try {
            tester.steer(steering);
        } catch (QueryException e) {
            String origin = "--goal";
            for (int i = 0; i < origins.size(); i++) {
                if (e.getMessage().contains("'" + steering.goals().get(i) + "'")) {
                    origin = origins.get(i);
                    break;
                }
            }
            throw usage.apply(origin + ": " + e.getMessage());
        } catch (UnsupportedModelException e) {
            throw usage.apply(e.getMessage());
        }
        SteeringReport report = tester.steeringReport();
        for (GoalStatus g : report.goals()) {
            if (g.state() == GoalStatus.State.UNREACHABLE) {
                out.println("dtron run: goal '" + g.text() + "' is unreachable: " + g.reason());
            }
        }
        if (!report.explored()) {
            out.println("dtron run: the planner explored the model only in part before the run (its limits: 200000"
                    + " states, 5 s): a goal it did not meet is not proved unreachable, and the run does not end on it");
        }
        out.flush();
    }

    /** The goals and the coverage after the run of {@code tester}, one line each; nothing without steering. */
    void report(OnlineTester tester, long unitMicros, PrintWriter out) {
        SteeringReport report = tester.steeringReport();
        if (steering == null || report == null) {
            return;
        }
        for (GoalStatus g : report.goals()) {
            out.println("goal '" + g.text() + "': " + switch (g.state()) {
                case REACHED -> "reached at t=" + units(g.micros(), unitMicros);
                case UNREACHABLE -> "unreachable" + (g.micros() >= 0 ? " from t=" + units(g.micros(), unitMicros)
                        : "") + ": " + g.reason();
                case OPEN -> "not reached";
            });
        }
        out.println("edges covered on inputs and outputs: " + report.edgesCovered() + " of " + report.edges()
                + " (environment: " + report.environmentEdgesCovered() + " of " + report.environmentEdges()
                + (report.environmentCoveredMicros() >= 0 ? ", all by t=" + units(report.environmentCoveredMicros(),
                unitMicros) + " after " + report.environmentCoveredInputs() + " inputs" : "") + ")");
        out.flush();
    }

    static String units(long micros, long unitMicros) {
        return Math.floorDiv(micros, unitMicros) + "." + String.format(Locale.ROOT, "%03d",
                Math.floorMod(micros, unitMicros) * 1000 / unitMicros);
    }
}
