package io.dtron.selenium;

import io.dtron.api.Dtron;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.internal.BrowserFailure;
import io.dtron.selenium.internal.Locators;
import io.dtron.selenium.internal.Messages;
import io.dtron.selenium.internal.StepWatch;
import java.net.http.HttpTimeoutException;
import java.time.Duration;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Objects;
import org.openqa.selenium.By;
import org.openqa.selenium.NoSuchElementException;
import org.openqa.selenium.NoSuchSessionException;
import org.openqa.selenium.NotFoundException;
import org.openqa.selenium.SessionNotCreatedException;
import org.openqa.selenium.TimeoutException;
import org.openqa.selenium.WebDriver;
import org.openqa.selenium.WebDriverException;
import org.openqa.selenium.WebElement;
import org.openqa.selenium.remote.UnreachableBrowserException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A Selenium adapter for one input of a model: it serves the channel named after its class (class
 * {@code LoginSomething} serves the model's {@code i_loginSomething}, the bus channel {@code loginSomething}),
 * with the variables of {@link ChannelVariables}, and does the step in a browser in {@link #execute}.
 *
 * <p>Every message is answered with one output {@value #RESULT_CHANNEL} (the model's {@code o_result}): after
 * {@code execute} returns its {@value #RESULT_CODE} is {@link #RESULT_OK}; when it throws, it is
 * {@link #RESULT_FAILED} and the exception's message is logged. An adapter may report its own code with
 * {@link #reportResult}, which turns the automatic report off for that message. When a step fails because of the
 * adapters' own machinery (the user's browser did not start, its session is gone, chromedriver or the browser
 * did not answer in time) or runs longer than the step timeout, no result is reported: the adapters log the
 * user, the step and what it waited for, and leave the bus, so that the tester ends the run INCONCLUSIVE rather
 * than blame the system under test. A step that runs longer than the slow-step threshold is logged while it
 * runs, with the WebDriver call it waits for (see {@link SeleniumAdapters}).
 *
 * <p>When the channel has a variable {@value #USER_VARIABLE}, each simulated user has a browser and a thread of
 * its own: the message runs in the browser of its user, after the earlier messages of that user, in parallel with
 * the other users, and the result carries the same {@value #USER_VARIABLE}. Without it, all messages run in the
 * browser of user 0, and the result carries {@value #RESULT_CODE} alone.
 *
 * <p>Subclasses are created by {@link SeleniumAdapters} with Guice: constructors and fields annotated
 * {@code @Inject} get {@code @Named("KEY")} strings from the adapters' properties and other adapters (one
 * instance of each). One instance serves all users; keep per-user state keyed by {@link #getUser()}.
 */
public abstract class AbstractSeleniumAdapter {
    /** The result code reported when {@link #execute} returns without reporting one. */
    public static final int RESULT_OK = 0;
    /** The result code reported when {@link #execute} throws. */
    public static final int RESULT_FAILED = 1;
    /** The bus channel of the results: the model's output {@code o_result}. */
    public static final String RESULT_CHANNEL = "result";
    /** The variable of the result channel that carries the code: the model's {@code o_result_resCode}. */
    public static final String RESULT_CODE = "resCode";
    /** The variable that names the simulated user, in inputs and results ({@code i_login_user}, ...). */
    public static final String USER_VARIABLE = "user";

    private static final Logger LOG = LoggerFactory.getLogger(AbstractSeleniumAdapter.class);
    private static final ThreadLocal<Call> CURRENT = new ThreadLocal<>();
    private static final IDtronChannel RESULT = IDtronChannel.of(RESULT_CHANNEL, RESULT_CODE);
    private static final IDtronChannel RESULT_FOR_USER = IDtronChannel.of(RESULT_CHANNEL, USER_VARIABLE, RESULT_CODE);

    private final IDtronChannel channel;
    private volatile AdapterRuntime runtime;
    private volatile DtronListener listener;

    /** The message being executed, on its user's thread. */
    private static final class Call {
        private final int user;
        private final boolean withUser;
        private final IDtronChannelValued message;
        private final long queuedNanos = System.nanoTime();
        private StepWatch.Step step;
        private boolean reported;

        Call(int user, boolean withUser, IDtronChannelValued message) {
            this.user = user;
            this.withUser = withUser;
            this.message = message;
        }
    }

    /**
     * Creates the adapter of the channel named after the class.
     *
     * @throws IllegalArgumentException if {@link ChannelVariables} names a variable twice or a name is no
     *                                  identifier
     */
    protected AbstractSeleniumAdapter() {
        this.channel = channelOf(getClass());
    }

    /**
     * Does the step of one message in the browser of its user ({@link #getWebDriver()}). Called on that user's
     * thread; returning reports {@link #RESULT_OK} unless {@link #reportResult} was called.
     *
     * @param message the input, with the variables of {@link ChannelVariables}
     * @throws Exception when the step fails: {@link #RESULT_FAILED} is reported and the message logged
     */
    protected abstract void execute(IDtronChannelValued message) throws Exception;

    /** Returns the template of the channel this adapter serves. */
    public final IDtronChannel getChannel() {
        return channel;
    }

    /**
     * Returns the browser of the current message's user, starting it if needed.
     *
     * @throws IllegalStateException if called outside {@link #execute}
     */
    protected final WebDriver getWebDriver() {
        return runtime().sessions().browser(call().user);
    }

    /**
     * Returns the bus member the adapter listens and reports on.
     *
     * @throws IllegalStateException if the adapter is not started
     */
    protected final Dtron getDtron() {
        return runtime().dtron();
    }

    /**
     * Returns the current message's user: its variable {@value #USER_VARIABLE}, or 0 if it has none.
     *
     * @throws IllegalStateException if called outside {@link #execute}
     */
    protected final int getUser() {
        return call().user;
    }

    /**
     * Finds an element in the current user's browser, waiting for it the browser's implicit wait.
     *
     * @param keyOrLocator a key of the adapters' properties whose value is a locator ({@code LOGIN_BUTTON}), or a
     *                     locator itself ({@code id:login-button}; also {@code name:}, {@code css:},
     *                     {@code xpath:}, {@code link:}, {@code partialLink:}, {@code class:}, {@code tag:})
     * @throws AdapterException      naming the key, the locator and the page if there is no such element
     * @throws IllegalStateException if called outside {@link #execute}
     */
    protected final WebElement findElement(String keyOrLocator) {
        Locators.Locator locator = runtime().locators().resolve(keyOrLocator);
        WebDriver driver = getWebDriver();
        try {
            return driver.findElement(locator.by());
        } catch (NoSuchElementException e) {
            throw new AdapterException("no element " + locator + " " + where(driver));
        }
    }

    /**
     * Finds a form field by its label's text (spaces normalised) in the current user's browser: the element
     * the {@code <label for=...>} names, or the field inside the label, or a field whose {@code aria-label} is
     * the text. Waits for it the browser's implicit wait.
     *
     * @throws AdapterException      naming the label and the page if there is no such field
     * @throws IllegalStateException if called outside {@link #execute}
     */
    protected final WebElement findInput(String label) {
        Objects.requireNonNull(label, "label");
        WebDriver driver = getWebDriver();
        String text = Locators.xpathLiteral(label);
        List<WebElement> candidates = driver.findElements(By.xpath("//label[normalize-space(.)=" + text + "]"
                + " | //*[(self::input or self::select or self::textarea) and @aria-label=" + text + "]"));
        for (WebElement candidate : candidates) {
            if (!candidate.getTagName().toLowerCase(Locale.ROOT).equals("label")) {
                return candidate;
            }
            String target = candidate.getDomAttribute("for");
            List<WebElement> fields = target != null && !target.isEmpty()
                    ? driver.findElements(By.xpath("//*[@id=" + Locators.xpathLiteral(target) + "]"))
                    : candidate.findElements(By.xpath(".//input | .//select | .//textarea"));
            if (!fields.isEmpty()) {
                return fields.get(0);
            }
        }
        throw new AdapterException("no field labelled '" + label + "' " + where(driver));
    }

    /**
     * Reports the result of the current message with this code instead of the automatic one.
     *
     * @throws IllegalStateException if called outside {@link #execute}, or twice for one message
     */
    protected final void reportResult(int code) {
        Call call = call();
        if (call.reported) {
            throw new IllegalStateException("the result of " + text(call.message) + " was already reported");
        }
        report(call, code);
    }

    @Override
    public String toString() {
        return getClass().getSimpleName() + "[" + channel + "]";
    }

    /** Returns the template of the channel that adapter class serves. */
    static IDtronChannel channelOf(Class<?> type) {
        String simple = type.getSimpleName();
        String name = simple.substring(0, 1).toLowerCase(Locale.ROOT) + simple.substring(1);
        ChannelVariables variables = type.getAnnotation(ChannelVariables.class);
        try {
            return IDtronChannel.of(name, variables == null ? new String[0] : variables.value());
        } catch (IllegalArgumentException e) {
            throw new IllegalArgumentException("adapter " + type.getName() + ": " + e.getMessage(), e);
        }
    }

    /** Starts listening on the bus; called once by {@link SeleniumAdapters}. */
    final void attach(AdapterRuntime adapterRuntime) {
        if (runtime != null) {
            throw new IllegalStateException(this + " is already started");
        }
        runtime = adapterRuntime;
        DtronListener l = new DtronListener(channel) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                deliver(message);
            }
        };
        adapterRuntime.dtron().declareOutputs(RESULT);
        adapterRuntime.dtron().addDtronListener(l);
        listener = l;
    }

    /** Stops listening; the messages already queued still run. */
    final void detach() {
        DtronListener l = listener;
        if (l != null) {
            listener = null;
            runtime.dtron().removeDtronListener(l);
        }
    }

    /** Called on the bus's listener thread: queues the message on its user's thread. */
    private void deliver(IDtronChannelValued message) {
        Integer user = message.getVariables().get(USER_VARIABLE);
        Call call = new Call(user == null ? 0 : user, user != null, message);
        if (!runtime.sessions().submit(call.user, () -> run(call))) {
            LOG.info("{} dropped {}: the adapters are closed", this, text(message));
        }
    }

    private void run(Call call) {
        CURRENT.set(call);
        StepWatch watch = runtime.sessions().watch();
        call.step = watch.begin(call.user, this + " on " + text(call.message), getClass(), call.queuedNanos);
        try {
            LOG.debug("{} starts {} for user {} after {} ms in the user's queue", this, text(call.message), call.user,
                    call.step.queuedMillis());
            execute(call.message);
            if (!call.reported) {
                report(call, RESULT_OK);
            }
            if (call.step.millis() >= watch.slowMillis()) {
                LOG.warn("{} did {} for user {} in {}", this, text(call.message), call.user, call.step.timing());
            } else {
                LOG.debug("{} did {} for user {} in {}", this, text(call.message), call.user, call.step.timing());
            }
        } catch (VirtualMachineError e) {
            // out of memory or threads: the adapters' own trouble; the user's thread ends, with a log
            runtime.giveUp().accept(this + " could not do " + text(call.message) + " for user " + call.user + ": "
                    + e);
            throw e;
        } catch (AdapterException | WebDriverException | AssertionError e) {
            failed(call, e, false);
        } catch (Throwable e) {
            failed(call, e, true);
        } finally {
            watch.end(call.step);
            CURRENT.remove();
        }
    }

    private void failed(Call call, Throwable e, boolean unexpected) {
        if (runtime.gaveUp().getAsBoolean()) {
            LOG.info("{} ended {} for user {} after the adapters gave up the run, reporting nothing: {}", this,
                    text(call.message), call.user, describe(e));
            return;
        }
        if (!call.reported && isMachinery(e)) {
            call.reported = true;
            call.step.reported();
            runtime.giveUp().accept(this + " could not do " + text(call.message) + " for user " + call.user + " after "
                    + call.step.timing() + ": " + describe(e));
            return;
        }
        boolean report = !call.reported;
        String text = "{} failed on {} for user {} after {}{}: {}";
        Object[] args = {this, text(call.message), call.user, call.step.timing(),
                report ? ", reporting " + RESULT_CODE + " " + RESULT_FAILED : "", describe(e)};
        if (unexpected) {
            LOG.error(text, withCause(args, e));
        } else {
            LOG.warn(text, args);
        }
        if (report) {
            report(call, RESULT_FAILED);
        }
    }

    /**
     * Whether a step failed because of the adapters' own machinery rather than the system under test: the user's
     * browser did not start, its session is gone, chromedriver or the browser did not answer in time.
     */
    static boolean isMachinery(Throwable e) {
        if (e instanceof BrowserFailure || e instanceof NoSuchSessionException
                || e instanceof SessionNotCreatedException || e instanceof UnreachableBrowserException) {
            return true;
        }
        if (e instanceof TimeoutException) {
            // chromedriver gave no answer in time; a WebDriverWait that timed out is about the page, not this
            for (Throwable c = e.getCause(); c != null; c = c.getCause()) {
                if (c instanceof java.util.concurrent.TimeoutException || c instanceof HttpTimeoutException) {
                    return true;
                }
            }
        }
        if (e instanceof WebDriverException && !(e instanceof NotFoundException)) {
            String first = Messages.firstLine(e.getMessage()).toLowerCase(Locale.ROOT);
            return first.contains("not reachable") || first.contains("disconnected: ")
                    || first.contains("timed out receiving message from renderer");
        }
        return false;
    }

    private void report(Call call, int code) {
        call.reported = true;
        if (call.step != null) {
            call.step.reported();
        }
        if (runtime.gaveUp().getAsBoolean()) {
            LOG.info("{} did not report {} {} for user {}: the adapters gave up the run", this, RESULT_CODE, code,
                    call.user);
            return;
        }
        IDtronChannel result = call.withUser ? RESULT_FOR_USER : RESULT;
        Map<String, Integer> values = call.withUser ? Map.of(USER_VARIABLE, call.user, RESULT_CODE, code)
                : Map.of(RESULT_CODE, code);
        try {
            runtime.dtron().send(result.constructValued(values));
        } catch (IllegalStateException e) {
            LOG.info("{} could not report {} {} for user {}: the bus is closed", this, RESULT_CODE, code, call.user);
        } catch (DtronException e) {
            runtime.giveUp().accept(this + " could not publish the result of " + text(call.message) + " for user "
                    + call.user + " (" + RESULT_CODE + " " + code + "): " + e.getMessage());
        }
    }

    private static String describe(Throwable e) {
        if (e instanceof AdapterException) {
            return e.getMessage();
        }
        String message = e instanceof WebDriverException ? Messages.firstLine(e.getMessage()) : e.getMessage();
        return e.getClass().getSimpleName() + (message == null || message.isEmpty() ? "" : ": " + message);
    }

    /** Returns a message as {@code press{user=0}}, without its sender. */
    private static String text(IDtronChannelValued message) {
        return message.getChannelName() + message.getVariables();
    }

    private static Object[] withCause(Object[] args, Throwable e) {
        Object[] all = new Object[args.length + 1];
        System.arraycopy(args, 0, all, 0, args.length);
        all[args.length] = e;
        return all;
    }

    private static String where(WebDriver driver) {
        String page;
        try {
            page = "on " + driver.getCurrentUrl() + " (\"" + driver.getTitle() + "\")";
        } catch (WebDriverException e) {
            page = "in a browser that does not answer";
        }
        Duration wait;
        try {
            wait = driver.manage().timeouts().getImplicitWaitTimeout();
        } catch (WebDriverException | UnsupportedOperationException e) {
            return page;
        }
        return page + " within " + wait.toMillis() + " ms";
    }

    private AdapterRuntime runtime() {
        AdapterRuntime r = runtime;
        if (r == null) {
            throw new IllegalStateException(this + " is not started: SeleniumAdapters starts it");
        }
        return r;
    }

    private static Call call() {
        Call call = CURRENT.get();
        if (call == null) {
            throw new IllegalStateException("only while an adapter executes a message");
        }
        return call;
    }
}
