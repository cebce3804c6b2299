package io.dtron.models.lamp;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import java.util.Arrays;
import java.util.List;

/**
 * The smart lamp of Uppaal TRON's manual, to test against TRON's {@code LightContr.xml} with its interface
 * {@code LightContr.trn}: inputs {@code grasp} and {@code release} (the user's hand on the lamp), output
 * {@code level} with variable {@code adapLevel} (the light level, 0 to 10), one model time unit = 1 ms there.
 *
 * <p>The lamp is the IUT part of that model, run deterministically: the input adapters ({@code graspAdapter},
 * {@code releaseAdapter}), the {@code interface} that tells a touch from a hold, the {@code switch} that turns
 * the light on and off on a touch, the {@code dimmer} that steps the level while the lamp is held, and the
 * output adapter ({@code levelAdapter}) that reports the level. Times below are in model time units and are
 * measured from when the lamp receives the input (one unit after the tester applies it):
 * <ul>
 *   <li>Every input reaches the lamp 1 unit after it is applied (the model's adapters allow 0 to 5).</li>
 *   <li>A grasp released less than 20 units after it reached the lamp is ignored (the model's {@code ignoring}
 *       location; it must be left for {@code touching} between 20 and 25 units, we leave it at exactly 20).</li>
 *   <li>A grasp released from 20 units on, and before 50, is a touch, recognised at once (the model's
 *       {@code touched} allows less than 5). A touch while the lamp is off turns it on at the old level and
 *       reports that level; a touch while it is on saves the level as the old level, turns it off and reports 0.
 *       The lamp starts off, at level 0, with old level 0, so the first touch reports level 0.</li>
 *   <li>A grasp still held 50 units after it reached the lamp is a hold (the model allows 50 to 55). If the
 *       dimmer last went down (or never ran), the hold sets the level to the old level, reports it at once and
 *       then counts up; if the dimmer last went up, the hold saves the level as the old level, reports nothing
 *       and counts down. Either way the lamp is on afterwards.</li>
 *   <li>While held, the level moves one step every 100 units (the model allows 100 to 105) and each step is
 *       reported. At 10 counting up, the next step, 100 units later, turns round and reports 9; at 0 counting
 *       down, it reports 1 (the model lets the turn and the step happen in the same instant).</li>
 *   <li>A release ends the hold at once (the model's {@code releasing} allows less than 5); the dimmer's next
 *       hold goes the other way.</li>
 *   <li>Each reported level is the level at the moment it was set, output 1 unit later (the model's
 *       {@code levelAdapter} copies it then and allows 0 to 5).</li>
 *   <li>When two things are due at the same instant, the one scheduled first happens first: a release arriving
 *       exactly 50 units after its grasp comes after the hold has started, and a release arriving exactly when
 *       a dimming step is due comes after that step. The model allows both orders.</li>
 *   <li>A grasp while the lamp is already grasped, or a release while it is not, is ignored. The model's
 *       {@code interface} cannot take them (its environment, the {@code user}, always alternates).</li>
 * </ul>
 *
 * <p>Variants, each differing from the correct lamp in one fault only:
 * <ul>
 *   <li>{@code correct} (the default): the behaviour above;</li>
 *   <li>{@code late}: reports every level 20 units after setting it instead of 1. The model allows 5, but its
 *       slack from an input to the output it causes is 15 units (5 in each adapter, less than 5 in
 *       {@code touched}), so a report only 10 units late could always be explained by slow adapters;</li>
 *   <li>{@code early}: a hold starts 40 units after the grasp reached the lamp instead of 50, so every level
 *       reported while held comes 10 units early: a hold that reports at its start does so 42 units after the
 *       grasp where the model wants at least 50;</li>
 *   <li>{@code wrong-level}: reports the level plus one;</li>
 *   <li>{@code missing}: reports nothing when a hold starts (the level the Dimmer sets from the old level); the
 *       model's {@code SampleUser} environment only ever holds, so this is a fault it reveals, where a missing
 *       report after a touch would go unnoticed.</li>
 * </ul>
 */
public final class SmartLamp implements Adapter {
    /** The model's epsilon: a grasp shorter than this is ignored. */
    private static final int EPSILON = 20;
    /** The model's delta: a grasp longer than this is a hold. */
    private static final int DELTA = 50;
    /** The model's delay: the time between two dimming steps. */
    private static final int DELAY = 100;
    /** The model's Max: the highest level. */
    private static final int MAX = 10;
    /** The time the lamp takes to receive an input and to report a level (the model's adapters allow 0 to 5). */
    private static final int LATENCY = 1;

    private enum Variant {
        CORRECT("correct", DELTA, LATENCY, 0, true),
        LATE("late", DELTA, 20, 0, true),
        EARLY("early", 40, LATENCY, 0, true),
        WRONG_LEVEL("wrong-level", DELTA, LATENCY, 1, true),
        MISSING("missing", DELTA, LATENCY, 0, false);

        private final String label;
        private final int holdAfter;
        private final int reportLatency;
        private final int reportOffset;
        private final boolean reportsHoldStart;

        Variant(String label, int holdAfter, int reportLatency, int reportOffset, boolean reportsHoldStart) {
            this.label = label;
            this.holdAfter = holdAfter;
            this.reportLatency = reportLatency;
            this.reportOffset = reportOffset;
            this.reportsHoldStart = reportsHoldStart;
        }
    }

    /** The model's {@code Interface} template, with {@code touched} and {@code releasing} left at once. */
    private enum Hand { IDLE, GRASPED, HOLDING }

    /** The model's {@code Dimmer} template, with its committed locations left at once. */
    private enum Dimmer { PASSIVE_UP, PASSIVE_DN, UP, DN }

    /** The names of the variants, the correct lamp first. */
    public static final List<String> VARIANTS = Arrays.stream(Variant.values()).map(v -> v.label).toList();

    private final Variant variant;
    private AdapterContext context;
    private boolean stopped;

    private Hand hand = Hand.IDLE;
    private long graspedAt;
    private TestClock.Scheduled holdStart;

    private Dimmer dimmer = Dimmer.PASSIVE_UP;
    private TestClock.Scheduled nextStep;

    private boolean on;
    private int level;
    private int oldLevel;

    /** The correct lamp. */
    public SmartLamp() {
        this(Variant.CORRECT.label);
    }

    /**
     * The lamp of the named variant.
     *
     * @throws IllegalArgumentException if {@code variant} is none of {@link #VARIANTS}
     */
    public SmartLamp(String variant) {
        this.variant = Arrays.stream(Variant.values()).filter(v -> v.label.equals(variant)).findFirst()
                .orElseThrow(() -> new IllegalArgumentException("unknown variant '" + variant + "' of "
                        + SmartLamp.class.getName() + "; known variants: " + String.join(", ", VARIANTS)));
    }

    /** The name of this lamp's variant. */
    public String variant() {
        return variant.label;
    }

    @Override
    public void start(AdapterContext context) {
        this.context = context;
    }

    @Override
    public void perform(Event input) {
        if (input.channel().equals("grasp")) {
            later(LATENCY, this::grasped);
        } else if (input.channel().equals("release")) {
            later(LATENCY, this::released);
        } else {
            throw new IllegalArgumentException("the lamp has no input '" + input.channel()
                    + "'; its inputs are grasp and release");
        }
    }

    @Override
    public void stop() {
        stopped = true;
    }

    /** The model's {@code setGrasp}: {@code idle -> ignoring}. */
    private void grasped() {
        if (hand != Hand.IDLE) {
            return;
        }
        hand = Hand.GRASPED;
        graspedAt = context.clock().nowMicros();
        holdStart = later(variant.holdAfter, this::startHold);
    }

    /** The model's {@code setRelease}: from {@code ignoring}, {@code touching} or {@code holding}. */
    private void released() {
        if (hand == Hand.GRASPED) {
            holdStart.cancel();
            hand = Hand.IDLE;
            if (context.clock().nowMicros() - graspedAt >= units(EPSILON)) {
                touch();
            }
        } else if (hand == Hand.HOLDING) {
            hand = Hand.IDLE;
            endHold();
        }
    }

    /** The model's {@code touch}, taken by the {@code Switch}. */
    private void touch() {
        if (on) {
            oldLevel = level;
            level = 0;
            on = false;
            setLevel();
        } else {
            level = oldLevel;
            on = true;
            setLevel();
        }
    }

    /** The model's {@code starthold}, sent by the {@code Interface} and taken by the {@code Dimmer}. */
    private void startHold() {
        hand = Hand.HOLDING;
        on = true;
        if (dimmer == Dimmer.PASSIVE_UP) {
            level = oldLevel;
            dimmer = Dimmer.UP;
            if (variant.reportsHoldStart) {
                setLevel();
            }
        } else {
            oldLevel = level;
            dimmer = Dimmer.DN;
        }
        nextStep = later(DELAY, this::step);
    }

    /** A dimming step of the {@code Dimmer}, turning round first at the top or the bottom. */
    private void step() {
        if (dimmer == Dimmer.UP && level == MAX) {
            dimmer = Dimmer.DN;
        } else if (dimmer == Dimmer.DN && level == 0) {
            dimmer = Dimmer.UP;
        }
        level += dimmer == Dimmer.UP ? 1 : -1;
        setLevel();
        nextStep = later(DELAY, this::step);
    }

    /** The model's {@code endhold}, sent by the {@code Interface} and taken by the {@code Dimmer}. */
    private void endHold() {
        nextStep.cancel();
        dimmer = dimmer == Dimmer.UP ? Dimmer.PASSIVE_DN : Dimmer.PASSIVE_UP;
    }

    /** The model's {@code setLevel}: the {@code levelAdapter} copies the level now and outputs it later. */
    private void setLevel() {
        Event output = Event.of("level", "adapLevel", level + variant.reportOffset);
        later(variant.reportLatency, () -> context.report(output));
    }

    private TestClock.Scheduled later(int units, Runnable task) {
        return context.clock().schedule(units(units), () -> {
            if (!stopped) {
                task.run();
            }
        });
    }

    private long units(int units) {
        return units * context.timeUnitMicros();
    }
}
