package io.dtron.models.streetlight.adapters;

import io.dtron.api.IDtronChannelValued;
import io.dtron.selenium.AbstractSeleniumAdapter;
import io.dtron.selenium.AdapterException;
import io.dtron.selenium.ChannelVariables;
import jakarta.inject.Inject;
import java.util.concurrent.TimeUnit;

/**
 * {@code i_check(user)}: waits until the result page has a final status and reports what it shows as the result
 * code: {@code 1000 * status + 10 * controller + state}, where status is 1 for OK, 2 for NOK and 3 for a page
 * still PENDING after {@value #WAIT_SECONDS} s, and state the model's number of the state shown.
 */
@ChannelVariables("user")
public final class Check extends AbstractSeleniumAdapter {
    /** How long the check waits for the controller to reach its new state. */
    public static final int WAIT_SECONDS = 4;

    @Inject
    StateLabels states;

    @Override
    protected void execute(IDtronChannelValued message) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_SECONDS);
        String status = findElement("RESULT_STATUS").getText();
        while (status.equals("PENDING") && System.nanoTime() < deadline) {
            Thread.sleep(100);
            getWebDriver().navigate().refresh();
            status = findElement("RESULT_STATUS").getText();
        }
        int statusDigit;
        switch (status) {
            case "OK":
                statusDigit = 1;
                break;
            case "NOK":
                statusDigit = 2;
                break;
            case "PENDING":
                statusDigit = 3;
                break;
            default:
                throw new AdapterException("the result page shows status '" + status + "'");
        }
        int controller;
        try {
            controller = Integer.parseInt(findElement("RESULT_CONTROLLER").getText());
        } catch (NumberFormatException e) {
            throw new AdapterException("the result page shows no controller number: " + e.getMessage());
        }
        int state = states.state(findElement("RESULT_STATE").getText());
        reportResult(1000 * statusDigit + 10 * controller + state);
    }
}
